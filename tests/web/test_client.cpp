#include "tests/web/test_client.hpp"

#include <cctype>
#include <cstdlib>
#include <future>

namespace fsd::web::test {

namespace {
// The HTTP status a server gives an upgrade request (Beast's handshake does not report it when declined).
unsigned upgrade_status(std::uint16_t port, const WsClient::Options& o) {
  std::string protos;
  for (const auto& p : o.subprotocols) protos += (protos.empty() ? "" : ", ") + p;
  std::vector<std::pair<std::string, std::string>> h{{"Connection", "Upgrade"},
                                                     {"Upgrade", "websocket"},
                                                     {"Sec-WebSocket-Version", "13"},
                                                     {"Sec-WebSocket-Key", "dGhlIHNhbXBsZSBub25jZQ=="}};
  if (!protos.empty()) h.emplace_back("Sec-WebSocket-Protocol", protos);
  if (!o.origin.empty()) h.emplace_back("Origin", o.origin);
  return http_request(port, http::verb::get, o.target, "", h).status;
}
}  // namespace

WsClient::WsClient(std::uint16_t port, Options options) : ws_(ioc_), keep_time_(options.keep_time) {
  auto& sock = beast::get_lowest_layer(ws_).socket();
  beast::error_code ec;
  sock.open(tcp::v4(), ec);
  if (options.receive_buffer > 0) sock.set_option(net::socket_base::receive_buffer_size(options.receive_buffer), ec);
  sock.connect(tcp::endpoint(net::ip::make_address("127.0.0.1"), port), ec);
  if (ec) return;
  ws_.set_option(websocket::stream_base::decorator([options](websocket::request_type& req) {
    std::string protos;
    for (const auto& p : options.subprotocols) protos += (protos.empty() ? "" : ", ") + p;
    if (!protos.empty()) req.set(http::field::sec_websocket_protocol, protos);
    if (!options.origin.empty()) req.set(http::field::origin, options.origin);
  }));
  ws_.read_message_max(64 * 1024 * 1024);
  websocket::response_type res;
  ws_.handshake(res, "127.0.0.1:" + std::to_string(port), options.target, ec);
  ok_ = !ec;
  status_ = ok_ ? res.result_int() : upgrade_status(port, options);
  if (ok_) subprotocol_ = std::string(res[http::field::sec_websocket_protocol]);
  work_.emplace(ioc_.get_executor());
  thread_ = std::thread([this] { ioc_.run(); });
  if (ok_ && options.read) start_reading();
}

WsClient::~WsClient() {
  net::post(ioc_, [this] {
    beast::error_code ec;
    beast::get_lowest_layer(ws_).socket().shutdown(tcp::socket::shutdown_both, ec);
    beast::get_lowest_layer(ws_).socket().close(ec);
  });
  work_.reset();
  thread_.join();
}

void WsClient::start_reading() {
  net::post(ioc_, [this] {
    if (reading_) return;
    reading_ = true;
    read_loop();
  });
}

void WsClient::read_loop() {
  ws_.async_read(buffer_, [this](beast::error_code ec, std::size_t) {
    std::lock_guard lock(m_);
    if (ec) {
      closed_ = true;
      if (ec == websocket::error::closed) close_code_ = ws_.reason().code;
      cv_.notify_all();
      return;
    }
    auto data = beast::buffers_to_string(buffer_.data());
    const bool time = ws_.got_binary() && !data.empty() && data[0] == 0x02;
    if (time) ++time_messages_;
    if (!time || keep_time_) inbox_.push_back({ws_.got_binary(), std::move(data)});
    ++received_;
    buffer_.consume(buffer_.size());
    cv_.notify_all();
    read_loop();
  });
}

std::optional<WsMessage> WsClient::next(std::chrono::milliseconds timeout) {
  std::unique_lock lock(m_);
  if (!cv_.wait_for(lock, timeout, [&] { return !inbox_.empty() || closed_; }) || inbox_.empty()) return std::nullopt;
  auto m = std::move(inbox_.front());
  inbox_.pop_front();
  return m;
}

std::optional<nlohmann::json> WsClient::next_op(const std::string& op, std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (true) {
    const auto left =
        std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    if (left <= 0ms) return std::nullopt;
    auto m = next(left);
    if (!m) return std::nullopt;
    if (m->binary) continue;
    auto j = m->json();
    if (j.value("op", "") == op) return j;
  }
}

std::optional<std::string> WsClient::next_binary(std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (true) {
    const auto left =
        std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    if (left <= 0ms) return std::nullopt;
    auto m = next(left);
    if (!m) return std::nullopt;
    if (m->binary) return m->data;
  }
}

namespace {
bool write_on(net::io_context& ioc, websocket::stream<beast::tcp_stream>& ws, const std::string& data, bool binary) {
  std::promise<beast::error_code> done;
  auto copy = std::make_shared<std::string>(data);
  net::post(ioc, [&, copy] {
    ws.binary(binary);
    ws.async_write(net::buffer(*copy), [&, copy](beast::error_code ec, std::size_t) { done.set_value(ec); });
  });
  auto f = done.get_future();
  if (f.wait_for(5s) != std::future_status::ready) return false;
  return !f.get();
}
}  // namespace

bool WsClient::send_text(const std::string& text) { return write_on(ioc_, ws_, text, false); }
bool WsClient::send_binary(const std::string& bytes) { return write_on(ioc_, ws_, bytes, true); }

std::optional<int> WsClient::wait_closed(std::chrono::milliseconds timeout) {
  std::unique_lock lock(m_);
  if (!cv_.wait_for(lock, timeout, [&] { return closed_; })) return std::nullopt;
  return close_code_;
}

std::size_t WsClient::time_messages() const {
  std::lock_guard lock(m_);
  return time_messages_;
}

std::size_t WsClient::received() const {
  std::lock_guard lock(m_);
  return received_;
}

HttpResult http_request(std::uint16_t port, http::verb method, const std::string& target, const std::string& body,
                        const std::vector<std::pair<std::string, std::string>>& headers) {
  try {
    return http_request_or_throw(port, method, target, body, headers);
  } catch (const beast::system_error&) {
    return {};  // the server closed the connection without an answer
  }
}

HttpResult http_request_or_throw(std::uint16_t port, http::verb method, const std::string& target,
                                 const std::string& body,
                                 const std::vector<std::pair<std::string, std::string>>& headers) {
  net::io_context ioc;
  beast::tcp_stream stream(ioc);
  stream.expires_after(5s);
  stream.connect(tcp::endpoint(net::ip::make_address("127.0.0.1"), port));
  http::request<http::string_body> req{method, target, 11};
  req.set(http::field::host, "127.0.0.1:" + std::to_string(port));
  for (const auto& [k, v] : headers) req.set(k, v);
  if (!body.empty() || method == http::verb::put) {
    req.body() = body;
    req.set(http::field::content_type, "application/json");
  }
  req.prepare_payload();
  http::write(stream, req);
  beast::flat_buffer buffer;
  http::response_parser<http::string_body> parser;
  parser.body_limit(64 * 1024 * 1024);
  if (method == http::verb::head) parser.skip(true);
  http::read(stream, buffer, parser);
  const auto& res = parser.get();
  HttpResult r;
  r.status = res.result_int();
  r.body = res.body();
  for (const auto& f : res) {
    std::string name(f.name_string());
    for (auto& c : name) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    r.headers[name] = std::string(f.value());
  }
  beast::error_code ec;
  stream.socket().shutdown(tcp::socket::shutdown_both, ec);
  return r;
}

namespace {
struct Tuning {
  double target_speed = 5.0;
  int lookahead_points = 10;
  bool use_gnss = true;
};
}  // namespace

std::shared_ptr<const ConfigSchema> test_schema() {
  static const auto section = ConfigSection<Tuning>("control")
                                  .number("target_speed", &Tuning::target_speed, 0.0, 20.0, "m/s", "Target speed", true)
                                  .integer("lookahead_points", &Tuning::lookahead_points, 1, 50, "", "Look-ahead", true)
                                  .boolean("use_gnss", &Tuning::use_gnss, "Use GNSS in lap 2", true);
  auto schema = std::make_shared<ConfigSchema>();
  section.describe(*schema);
  return schema;
}

}  // namespace fsd::web::test

namespace fsd::web::test {

WebConfig TestServer::base_config() {
  ::unsetenv("FSD_WEB_TOKEN");  // the environment would override the token under test
  WebConfig c;
  c.bind = "127.0.0.1";
  c.port = 0;
  c.token = kToken;
  c.web_root = "/nonexistent/fsd-web-root";
  c.idle_timeout_s = 30;
  return c;
}

TestServer::TestServer(const WebConfig& cfg) : server(std::make_unique<WebServer>(cfg, params, clock)) {
  server->start();
}

}  // namespace fsd::web::test
