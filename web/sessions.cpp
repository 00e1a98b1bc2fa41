#include "web/sessions.hpp"

#include <algorithm>

#include "common/logging.hpp"
#include "web/auth.hpp"
#include "web/static_files.hpp"
#include "web/url.hpp"

namespace fsd::web {

namespace {

constexpr std::size_t kReadChunk = 16 * 1024;
constexpr double kAbuseAllowance = 10.0;     // protocol violations tolerated in a burst
constexpr double kAbuseRefillPerS = 0.5;     // and forgiven at this rate
constexpr std::size_t kControlQueue = 1024;  // protocol replies waiting for a client

std::string endpoint_text(const tcp::socket& s) {
  beast::error_code ec;
  const auto ep = s.remote_endpoint(ec);
  if (ec) return "unknown";
  const auto addr = ep.address();
  return (addr.is_v6() ? "[" + addr.to_string() + "]" : addr.to_string()) + ":" + std::to_string(ep.port());
}

// The Foxglove subprotocol the client offered, under either of its names (the classic one preferred), or empty.
std::string_view offered_foxglove(const HttpRequest& req) {
  const auto h = req[http::field::sec_websocket_protocol];
  bool sdk = false;
  for (const auto& p : split_list({h.data(), h.size()})) {
    if (p == foxglove::kSubprotocol) return foxglove::kSubprotocol;
    sdk = sdk || p == foxglove::kSdkSubprotocol;
  }
  return sdk ? foxglove::kSdkSubprotocol : std::string_view{};
}

bool quiet(const beast::error_code& ec) {
  return ec == net::error::operation_aborted || ec == websocket::error::closed || ec == beast::error::timeout ||
         ec == net::error::eof || ec == net::error::connection_reset || ec == net::error::broken_pipe ||
         ec == http::error::end_of_stream;
}

}  // namespace

// ---------------------------------------------------------------------------------------------- SessionTracker

void SessionTracker::add(const std::shared_ptr<Closable>& s) {
  std::lock_guard lock(m_);
  live_[s.get()] = s;
}

void SessionTracker::remove(const Closable* s) {
  {
    std::lock_guard lock(m_);
    live_.erase(s);
  }
  cv_.notify_all();
}

void SessionTracker::shutdown_all() {
  std::vector<std::shared_ptr<Closable>> all;
  {
    std::lock_guard lock(m_);
    for (auto& [_, w] : live_)
      if (auto s = w.lock()) all.push_back(std::move(s));
  }
  for (auto& s : all) s->shutdown();
}

bool SessionTracker::wait_empty(std::chrono::milliseconds timeout) {
  std::unique_lock lock(m_);
  return cv_.wait_for(lock, timeout, [&] { return live_.empty(); });
}

std::size_t SessionTracker::size() const {
  std::lock_guard lock(m_);
  return live_.size();
}

// ----------------------------------------------------------------------------------------------- ServerContext

ServerContext::ServerContext(const WebConfig& cfg, ParamRegistry& params)
    : config(cfg),
      allowed_origins(split_list(cfg.allowed_origins)),
      max_http_connections(4 * cfg.max_clients + 16),
      messages_sent(metrics.counter("fsd_web_messages_sent_total", "WebSocket messages written to clients")),
      bytes_sent(metrics.counter("fsd_web_bytes_sent_total", "WebSocket payload bytes written to clients")),
      connections_refused(metrics.counter("fsd_web_connections_refused_total",
                                          "TCP connections closed at once because too many were open")) {
  HubLimits limits;
  limits.max_clients = cfg.max_clients;
  limits.telemetry_queue = static_cast<std::size_t>(cfg.client_send_queue);
  limits.control_queue = kControlQueue;
  hub = std::make_shared<Hub>(params, effective_token(cfg), metrics, limits, "fsd-daemon");
  hub->listen_to_params();
  api = std::make_unique<HttpApi>(*hub, StaticFiles(locate_web_root(cfg.web_root)), allowed_origins);
  metrics.gauge_callback("fsd_web_http_connections", "Open HTTP connections",
                         [this] { return static_cast<double>(http_connections.load()); });
}

// ---------------------------------------------------------------------------------------------------- Listener

Listener::Listener(net::io_context& ioc, const tcp::endpoint& endpoint, std::shared_ptr<ServerContext> ctx)
    : ioc_(ioc), acceptor_(net::make_strand(ioc)), retry_(acceptor_.get_executor()), ctx_(std::move(ctx)) {
  beast::error_code ec;
  const auto fail = [&](const char* what) {
    throw std::runtime_error("web: cannot " + std::string(what) + " " + endpoint.address().to_string() + ":" +
                             std::to_string(endpoint.port()) + ": " + ec.message());
  };
  acceptor_.open(endpoint.protocol(), ec);
  if (ec) fail("open");
  acceptor_.set_option(net::socket_base::reuse_address(true), ec);
  acceptor_.bind(endpoint, ec);
  if (ec) fail("bind");
  acceptor_.listen(net::socket_base::max_listen_connections, ec);
  if (ec) fail("listen on");
  port_ = acceptor_.local_endpoint().port();
}

void Listener::run() {
  net::dispatch(acceptor_.get_executor(), [self = shared_from_this()] { self->do_accept(); });
}

void Listener::shutdown() {
  net::post(acceptor_.get_executor(), [self = shared_from_this()] {
    beast::error_code ec;
    self->acceptor_.close(ec);
    self->retry_.cancel();
  });
}

void Listener::do_accept() {
  acceptor_.async_accept(net::make_strand(ioc_), beast::bind_front_handler(&Listener::on_accept, shared_from_this()));
}

void Listener::on_accept(beast::error_code ec, tcp::socket socket) {
  if (!acceptor_.is_open()) return;
  if (ec) {
    // Out of file descriptors and the like: say so and try again shortly rather than spin.
    logger("web")->warn("accept failed: {}", ec.message());
    retry_.expires_after(std::chrono::milliseconds(100));
    retry_.async_wait([self = shared_from_this()](beast::error_code e) {
      if (!e) self->do_accept();
    });
    return;
  }
  if (ctx_->http_connections.load() >= ctx_->max_http_connections) {
    ctx_->connections_refused.inc();
    beast::error_code ignored;
    socket.close(ignored);
  } else {
    auto session = std::make_shared<HttpSession>(std::move(socket), ctx_);
    ctx_->tracker.add(session);
    session->run();
  }
  do_accept();
}

// ------------------------------------------------------------------------------------------------- HttpSession

HttpSession::HttpSession(tcp::socket&& socket, std::shared_ptr<ServerContext> ctx)
    : stream_(std::move(socket)), ctx_(std::move(ctx)) {
  peer_ = endpoint_text(stream_.socket());
  ctx_->http_connections.fetch_add(1);
}

HttpSession::~HttpSession() {
  ctx_->http_connections.fetch_sub(1);
  ctx_->tracker.remove(this);
}

void HttpSession::run() {
  net::dispatch(stream_.get_executor(), [self = shared_from_this()] { self->do_read(); });
}

void HttpSession::shutdown() {
  net::post(stream_.get_executor(), [self = shared_from_this()] {
    if (!self->upgraded_) self->close_socket();
  });
}

void HttpSession::close_socket() {
  beast::error_code ec;
  stream_.socket().shutdown(tcp::socket::shutdown_both, ec);
  stream_.close();
}

void HttpSession::do_read() {
  parser_.emplace();
  parser_->body_limit(static_cast<std::uint64_t>(ctx_->config.max_frame_bytes));
  parser_->header_limit(16 * 1024);
  stream_.expires_after(std::chrono::seconds(ctx_->config.idle_timeout_s));
  http::async_read(stream_, buffer_, *parser_, beast::bind_front_handler(&HttpSession::on_read, shared_from_this()));
}

void HttpSession::on_read(beast::error_code ec, std::size_t) {
  if (ec == http::error::body_limit || ec == http::error::header_limit) {
    HttpRequest req;
    req.version(11);
    req.keep_alive(false);
    auto res = json_response(
        req,
        ec == http::error::body_limit ? http::status::payload_too_large : http::status::request_header_fields_too_large,
        {{"error", ec.message()}});
    res.keep_alive(false);
    send(std::move(res));
    return;
  }
  if (ec) {
    if (!quiet(ec)) logger("web")->debug("http {}: {}", peer_, ec.message());
    close_socket();
    return;
  }
  HttpRequest req = parser_->release();
  if (websocket::is_upgrade(req)) {
    upgrade(std::move(req));
    return;
  }
  send(ctx_->api->handle(req, peer_));
}

void HttpSession::send(HttpResponse res) {
  res_ = std::make_shared<HttpResponse>(std::move(res));
  const bool close = res_->need_eof();
  http::async_write(stream_, *res_, beast::bind_front_handler(&HttpSession::on_write, shared_from_this(), close));
}

void HttpSession::on_write(bool close, beast::error_code ec, std::size_t) {
  res_.reset();
  if (ec || close) {
    close_socket();
    return;
  }
  do_read();
}

void HttpSession::refuse(const HttpRequest& req, http::status status, const std::string& why) {
  auto res = make_response(req, status, "text/plain; charset=utf-8", why + "\n");
  res.keep_alive(false);
  send(std::move(res));
}

void HttpSession::upgrade(HttpRequest req) {
  const auto origin = req[http::field::origin];
  const auto host = req[http::field::host];
  if (!origin_allowed({origin.data(), origin.size()}, {host.data(), host.size()}, ctx_->allowed_origins)) {
    logger("web")->warn("{}: WebSocket from origin '{}' refused", peer_, std::string(origin));
    refuse(req, http::status::forbidden, "origin not allowed (web.allowed_origins)");
    return;
  }
  if (offered_foxglove(req).empty()) {
    refuse(req, http::status::bad_request,
           "this server speaks the Foxglove WebSocket protocol: offer the subprotocol foxglove.websocket.v1 (or "
           "foxglove.sdk.v1)");
    return;
  }
  const auto target = split_target({req.target().data(), req.target().size()});
  const auto token = query_param(target.query, "token");
  const bool token_ok = token && ctx_->hub->authorised(*token);
  if (!ctx_->hub->try_admit()) {
    logger("web")->warn("{}: WebSocket refused, {} clients connected", peer_, ctx_->config.max_clients);
    refuse(req, http::status::service_unavailable, "too many clients");
    return;
  }
  upgraded_ = true;
  stream_.expires_never();
  auto ws = std::make_shared<WsSession>(std::move(stream_), ctx_, peer_, token_ok, token && !token_ok);
  ctx_->tracker.add(ws);
  ws->run(std::move(req));
}

// --------------------------------------------------------------------------------------------------- WsSession

WsSession::WsSession(beast::tcp_stream&& stream, std::shared_ptr<ServerContext> ctx, std::string peer, bool token_ok,
                     bool token_wrong)
    : ws_(std::move(stream)), ctx_(std::move(ctx)), token_wrong_(token_wrong) {
  peer_ = std::make_shared<Peer>();
  peer_->state = ctx_->hub->make_client_state();
  peer_->address = std::move(peer);
  peer_->token_ok = token_ok;
  msg_tokens_ = ctx_->config.max_incoming_msgs_per_s;
  abuse_tokens_ = kAbuseAllowance;
  last_refill_ = std::chrono::steady_clock::now();
}

WsSession::~WsSession() {
  finish();
  ctx_->hub->release();
  ctx_->tracker.remove(this);
}

void WsSession::run(HttpRequest req) {
  req_ = std::move(req);
  peer_->wake = [weak = weak_from_this()] {
    if (auto self = weak.lock()) net::post(self->ws_.get_executor(), [self] { self->do_write(); });
  };
  auto timeouts = websocket::stream_base::timeout::suggested(beast::role_type::server);
  timeouts.handshake_timeout = std::chrono::seconds(10);
  timeouts.idle_timeout = std::chrono::seconds(ctx_->config.idle_timeout_s);
  timeouts.keep_alive_pings = true;  // a live client answers the pings, a dead one times out
  ws_.set_option(timeouts);
  ws_.set_option(websocket::stream_base::decorator(
      [protocol = std::string(offered_foxglove(req_))](websocket::response_type& res) {
        res.set(http::field::sec_websocket_protocol, protocol);
        res.set(http::field::server, "fsd");
      }));
  // Beyond this Beast itself fails the connection (close code 1009); up to it we read and drop oversize
  // messages so that the client hears why.
  ws_.read_message_max(static_cast<std::uint64_t>(ctx_->config.max_frame_bytes) * 16);
  net::dispatch(ws_.get_executor(), [self = shared_from_this()] {
    self->ws_.async_accept(self->req_, beast::bind_front_handler(&WsSession::on_accept, self));
  });
}

void WsSession::shutdown() {
  net::post(ws_.get_executor(), [self = shared_from_this()] {
    if (self->accepted_) {
      self->close_with(websocket::close_code::going_away, "server shutting down");
    } else {
      beast::error_code ec;
      beast::get_lowest_layer(self->ws_).socket().close(ec);
    }
  });
}

void WsSession::on_accept(beast::error_code ec) {
  req_ = {};
  if (ec) {
    logger("web")->debug("WebSocket handshake with {} failed: {}", peer_->address, ec.message());
    return;
  }
  accepted_ = true;
  ctx_->hub->add_peer(peer_);
  if (token_wrong_) {
    logger("web")->warn("{} connected with a wrong token: read-only", peer_->address);
    ctx_->hub->send_status(*peer_, foxglove::StatusLevel::Warning,
                           "the token in the URL is not valid: this connection is read-only");
  }
  do_read();
}

void WsSession::do_read() {
  ws_.async_read_some(rbuf_, kReadChunk, beast::bind_front_handler(&WsSession::on_read, shared_from_this()));
}

void WsSession::on_read(beast::error_code ec, std::size_t) {
  if (ec) {
    if (ec == websocket::error::message_too_big) ctx_->hub->note_protocol_error();
    if (!quiet(ec)) logger("web")->debug("{}: {}", peer_->address, ec.message());
    finish();
    return;
  }
  if (closing_) {
    rbuf_.clear();
    do_read();
    return;
  }
  if (!discarding_ && rbuf_.size() > static_cast<std::size_t>(ctx_->config.max_frame_bytes)) discarding_ = true;
  if (discarding_) rbuf_.clear();
  if (!ws_.is_message_done()) {
    do_read();
    return;
  }
  if (discarding_) {
    discarding_ = false;
    refuse_message("message larger than " + std::to_string(ctx_->config.max_frame_bytes) + " bytes refused");
  } else {
    on_message();
  }
  rbuf_.clear();
  if (peer_->state->overflowed()) close_with(websocket::close_code::policy_error, "client does not read its replies");
  if (!closing_) do_read();
}

void WsSession::on_message() {
  // Refill both token buckets for the time since the last message.
  const auto now = std::chrono::steady_clock::now();
  const double dt = std::chrono::duration<double>(now - last_refill_).count();
  last_refill_ = now;
  const double rate = ctx_->config.max_incoming_msgs_per_s;
  msg_tokens_ = std::min(rate, msg_tokens_ + dt * rate);
  abuse_tokens_ = std::min(kAbuseAllowance, abuse_tokens_ + dt * kAbuseRefillPerS);
  if (msg_tokens_ < 1.0) {
    // Over the rate: drop it; tell the client (and count a violation) at most once a second.
    if (now - last_rate_status_ >= std::chrono::seconds(1)) {
      last_rate_status_ = now;
      refuse_message("more than " + std::to_string(ctx_->config.max_incoming_msgs_per_s) +
                     " messages per second: messages dropped");
    }
    return;
  }
  msg_tokens_ -= 1.0;
  if (!ws_.got_text()) {
    refuse_message("binary messages need the clientPublish or services capability, which this server does not offer");
    return;
  }
  const auto data = rbuf_.cdata();
  if (!ctx_->hub->on_text(*peer_, {static_cast<const char*>(data.data()), data.size()})) violation("refused message");
}

void WsSession::refuse_message(const std::string& why) {
  ctx_->hub->note_protocol_error();
  ctx_->hub->send_status(*peer_, foxglove::StatusLevel::Error, why);
  violation(why);
}

void WsSession::violation(const std::string& what) {
  abuse_tokens_ -= 1.0;
  if (abuse_tokens_ < 0.0) {
    logger("web")->warn("{}: closing after repeated protocol errors (last: {})", peer_->address, what);
    close_with(websocket::close_code::policy_error, "too many protocol errors");
  }
}

void WsSession::close_with(websocket::close_code code, const std::string& reason) {
  if (closing_ || finished_) return;
  closing_ = true;
  ws_.async_close(websocket::close_reason(code, reason),
                  [self = shared_from_this()](beast::error_code) { self->finish(); });
}

void WsSession::finish() {
  if (finished_) return;
  finished_ = true;
  if (accepted_) {
    ctx_->hub->remove_peer(peer_.get());
    logger("web")->info("client {} disconnected ({} telemetry messages dropped)", peer_->address,
                        peer_->state->dropped());
  }
  peer_->state->close();
}

void WsSession::do_write() {
  if (writing_) return;  // a write is in flight; its completion continues the chain
  if (closing_ || finished_) return;
  auto next = peer_->state->next();
  if (!next) return;
  writing_ = std::move(next);
  ws_.binary(writing_->binary);
  auto done = beast::bind_front_handler(&WsSession::on_write, shared_from_this());
  if (writing_->header_size) {
    const std::array<net::const_buffer, 2> bufs{net::buffer(writing_->header.data(), writing_->header_size),
                                                net::buffer(*writing_->body)};
    ws_.async_write(bufs, std::move(done));
  } else {
    ws_.async_write(net::buffer(*writing_->body), std::move(done));
  }
}

void WsSession::on_write(beast::error_code ec, std::size_t bytes) {
  writing_.reset();
  if (ec) {
    if (!quiet(ec)) logger("web")->debug("{}: write: {}", peer_->address, ec.message());
    finish();
    return;
  }
  ctx_->messages_sent.inc();
  ctx_->bytes_sent.inc(bytes);
  if (peer_->state->overflowed()) {
    close_with(websocket::close_code::policy_error, "client does not read its replies");
    return;
  }
  do_write();
}

}  // namespace fsd::web
