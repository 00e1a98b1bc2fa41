#pragma once
// Test helpers: a real Beast WebSocket client that reads on its own thread, a one-shot HTTP client, and a
// parameter registry with a few tunable keys.
#include <chrono>
#include <condition_variable>
#include <deque>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include <boost/asio.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/websocket.hpp>
#include <nlohmann/json.hpp>

#include "common/config.hpp"
#include "common/params.hpp"

namespace fsd::web::test {

namespace net = boost::asio;
namespace beast = boost::beast;
namespace websocket = boost::beast::websocket;
namespace http = boost::beast::http;
using tcp = net::ip::tcp;
using namespace std::chrono_literals;

struct WsMessage {
  bool binary = false;
  std::string data;
  nlohmann::json json() const { return nlohmann::json::parse(data); }
};

class WsClient {
 public:
  struct Options {
    std::string target = "/";
    std::vector<std::string> subprotocols{"foxglove.websocket.v1"};
    std::string origin;      // Origin header when not empty
    bool read = true;        // false: never read (a stalled client)
    int receive_buffer = 0;  // SO_RCVBUF before connecting, when > 0
    bool keep_time = false;  // keep the server's binary time messages (dropped by default, but counted)
  };
  // Connects and does the handshake. handshake_ok() tells whether the server accepted; status() gives the
  // HTTP status of the server's answer either way.
  explicit WsClient(std::uint16_t port, Options options);
  explicit WsClient(std::uint16_t port) : WsClient(port, Options{}) {}
  ~WsClient();

  bool handshake_ok() const { return ok_; }
  unsigned status() const { return status_; }
  std::string accepted_subprotocol() const { return subprotocol_; }

  std::optional<WsMessage> next(std::chrono::milliseconds timeout = 3000ms);
  // The next text message whose "op" is `op`, skipping others; nullopt on timeout.
  std::optional<nlohmann::json> next_op(const std::string& op, std::chrono::milliseconds timeout = 3000ms);
  // The next binary message, skipping text; nullopt on timeout.
  std::optional<std::string> next_binary(std::chrono::milliseconds timeout = 3000ms);
  bool send_text(const std::string& text);
  bool send_binary(const std::string& bytes);
  void start_reading();
  // Waits until the server closed the connection; the close code then (0 when none was received).
  std::optional<int> wait_closed(std::chrono::milliseconds timeout = 3000ms);
  std::size_t received() const;
  std::size_t time_messages() const;

 private:
  void read_loop();

  net::io_context ioc_;
  websocket::stream<beast::tcp_stream> ws_;
  std::optional<net::executor_work_guard<net::io_context::executor_type>> work_;
  std::thread thread_;
  beast::flat_buffer buffer_;
  mutable std::mutex m_;
  std::condition_variable cv_;
  std::deque<WsMessage> inbox_;
  std::size_t received_ = 0, time_messages_ = 0;
  bool keep_time_ = false;
  bool ok_ = false, closed_ = false, reading_ = false;
  unsigned status_ = 0;
  int close_code_ = 0;
  std::string subprotocol_;
};

struct HttpResult {
  unsigned status = 0;
  std::string body;
  std::map<std::string, std::string> headers;  // lower-case names
};
// status 0 when the server closed the connection without answering.
HttpResult http_request(std::uint16_t port, http::verb method, const std::string& target, const std::string& body = "",
                        const std::vector<std::pair<std::string, std::string>>& headers = {});
HttpResult http_request_or_throw(std::uint16_t port, http::verb method, const std::string& target,
                                 const std::string& body,
                                 const std::vector<std::pair<std::string, std::string>>& headers);

// A configuration with tunable parameters: "control.target_speed" (number 0…20 m/s, default 5),
// "control.lookahead_points" (integer 1…50, default 10), "control.use_gnss" (boolean, default true).
std::shared_ptr<const ConfigSchema> test_schema();

}  // namespace fsd::web::test

#include "common/clock.hpp"
#include "web/config.hpp"
#include "web/server.hpp"

namespace fsd::web::test {

inline constexpr const char* kToken = "s3cret-token";

// A started server on 127.0.0.1 and a free port, with the test parameters and the token kToken.
struct TestServer {
  static WebConfig base_config();
  explicit TestServer(const WebConfig& cfg = base_config());
  std::uint16_t port() const { return server->port(); }

  RealClock clock;
  Config config{test_schema()};
  ParamRegistry params{config, &clock};
  std::unique_ptr<WebServer> server;
};

}  // namespace fsd::web::test
