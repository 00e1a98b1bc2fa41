#pragma once
// The Beast side of the server: the listener, one HTTP session per connection, and the WebSocket session a
// connection becomes after the Foxglove handshake. Each connection runs on its own strand of the server's
// io_context; publishers reach a WebSocket session only through its ClientState and a posted wake-up.
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <unordered_map>
#include <utility>  // before Asio: Boost 1.74's awaitable.hpp uses std::exchange without including it
#include <vector>

#include <boost/asio.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/websocket.hpp>

#include "web/config.hpp"
#include "web/http_api.hpp"
#include "web/hub.hpp"
#include "web/metrics.hpp"

namespace fsd::web {

namespace net = boost::asio;
namespace beast = boost::beast;
namespace websocket = boost::beast::websocket;
using tcp = net::ip::tcp;

// Something the server closes when it stops.
class Closable {
 public:
  virtual ~Closable() = default;
  virtual void shutdown() = 0;  // thread-safe: posts the close to the session's strand
};

// The live sessions, so that stop() can close them and wait until they are gone.
class SessionTracker {
 public:
  void add(const std::shared_ptr<Closable>& s);
  void remove(const Closable* s);
  void shutdown_all();
  bool wait_empty(std::chrono::milliseconds timeout);
  std::size_t size() const;

 private:
  mutable std::mutex m_;
  std::condition_variable cv_;
  std::unordered_map<const Closable*, std::weak_ptr<Closable>> live_;
};

// What every session shares; each session holds it alive.
struct ServerContext {
  ServerContext(const WebConfig& cfg, ParamRegistry& params);
  const WebConfig config;
  const std::vector<std::string> allowed_origins;
  Metrics metrics;
  std::shared_ptr<Hub> hub;
  std::unique_ptr<HttpApi> api;
  SessionTracker tracker;
  std::atomic<int> http_connections{0};
  const int max_http_connections;
  Counter& messages_sent;
  Counter& bytes_sent;
  Counter& connections_refused;
};

class Listener : public std::enable_shared_from_this<Listener> {
 public:
  // Binds and listens; throws std::runtime_error naming the address when that fails.
  Listener(net::io_context& ioc, const tcp::endpoint& endpoint, std::shared_ptr<ServerContext> ctx);
  void run();
  void shutdown();  // thread-safe
  std::uint16_t port() const { return port_; }

 private:
  void do_accept();
  void on_accept(beast::error_code ec, tcp::socket socket);

  net::io_context& ioc_;
  tcp::acceptor acceptor_;
  net::steady_timer retry_;
  std::shared_ptr<ServerContext> ctx_;
  std::uint16_t port_ = 0;
};

class HttpSession : public std::enable_shared_from_this<HttpSession>, public Closable {
 public:
  HttpSession(tcp::socket&& socket, std::shared_ptr<ServerContext> ctx);
  ~HttpSession() override;
  void run();
  void shutdown() override;

 private:
  void do_read();
  void on_read(beast::error_code ec, std::size_t bytes);
  void send(HttpResponse res);
  void on_write(bool close, beast::error_code ec, std::size_t bytes);
  void upgrade(HttpRequest req);
  void refuse(const HttpRequest& req, http::status status, const std::string& why);
  void close_socket();

  beast::tcp_stream stream_;
  beast::flat_buffer buffer_;
  std::optional<http::request_parser<http::string_body>> parser_;
  std::shared_ptr<ServerContext> ctx_;
  std::string peer_;
  std::shared_ptr<HttpResponse> res_;
  bool upgraded_ = false;
};

class WsSession : public std::enable_shared_from_this<WsSession>, public Closable {
 public:
  // The caller has taken a client slot (Hub::try_admit); the session gives it back when it ends.
  WsSession(beast::tcp_stream&& stream, std::shared_ptr<ServerContext> ctx, std::string peer, bool token_ok,
            bool token_wrong);
  ~WsSession() override;
  void run(HttpRequest req);
  void shutdown() override;

 private:
  void on_accept(beast::error_code ec);
  void do_read();
  void on_read(beast::error_code ec, std::size_t bytes);
  void on_message();
  void do_write();
  void on_write(beast::error_code ec, std::size_t bytes);
  void refuse_message(const std::string& why);  // status error + violation
  void violation(const std::string& what);
  void close_with(websocket::close_code code, const std::string& reason);
  void finish();

  websocket::stream<beast::tcp_stream> ws_;
  std::shared_ptr<ServerContext> ctx_;
  std::shared_ptr<Peer> peer_;
  HttpRequest req_;
  beast::flat_buffer rbuf_;
  std::optional<OutMessage> writing_;
  bool token_wrong_ = false;
  bool accepted_ = false;
  bool closing_ = false;
  bool finished_ = false;
  bool discarding_ = false;  // the message being read is over max_frame_bytes: read it to its end, drop it
  // Token buckets: incoming message rate, and protocol violations (running dry closes the connection).
  double msg_tokens_ = 0, abuse_tokens_ = 0;
  std::chrono::steady_clock::time_point last_refill_;
  std::chrono::steady_clock::time_point last_rate_status_{};
};

}  // namespace fsd::web
