#include "web/server.hpp"

#include <thread>

#include "common/clock.hpp"
#include "common/logging.hpp"
#include "web/sessions.hpp"

namespace fsd::web {

namespace {
constexpr auto kTimePeriod = std::chrono::milliseconds(100);  // Foxglove "time" messages, 10 Hz
constexpr auto kDrainPeriod = std::chrono::milliseconds(2);   // publish → clients' queues
}  // namespace

struct WebServer::Impl {
  Impl(const WebConfig& cfg, ParamRegistry& params, Clock& clk)
      : ctx(std::make_shared<ServerContext>(cfg, params)), clock(clk), time_timer(ioc), drain_timer(ioc) {}

  // The publishers' outbox is drained on this timer rather than on a signal from them: publishing stays a
  // wait-free push, at the price of up to kDrainPeriod of latency.
  void tick_drain() {
    drain_timer.expires_after(kDrainPeriod);
    drain_timer.async_wait([this](beast::error_code ec) {
      if (ec) return;
      ctx->hub->drain();
      tick_drain();
    });
  }

  void tick_time() {
    time_timer.expires_after(kTimePeriod);
    time_timer.async_wait([this](beast::error_code ec) {
      if (ec) return;
      if (ctx->hub->peer_count() > 0) ctx->hub->publish_time(clock.now());
      tick_time();
    });
  }

  std::shared_ptr<ServerContext> ctx;  // declared first: outlives the io_context and the sessions it holds
  Clock& clock;
  net::io_context ioc;
  std::optional<net::executor_work_guard<net::io_context::executor_type>> work;
  net::steady_timer time_timer;
  net::steady_timer drain_timer;
  std::shared_ptr<Listener> listener;
  std::vector<std::thread> threads;
  bool started = false, stopped = false;
};

WebServer::WebServer(const WebConfig& cfg, ParamRegistry& params, Clock& clock)
    : impl_(std::make_unique<Impl>(cfg, params, clock)) {}

WebServer::~WebServer() { stop(); }

void WebServer::start() {
  auto& d = *impl_;
  if (d.started) return;
  const auto& cfg = d.ctx->config;
  beast::error_code ec;
  const auto address = net::ip::make_address(cfg.bind, ec);
  if (ec) throw std::runtime_error("web: bad bind address '" + cfg.bind + "': " + ec.message());
  d.listener = std::make_shared<Listener>(d.ioc, tcp::endpoint(address, static_cast<std::uint16_t>(cfg.port)), d.ctx);
  d.started = true;
  d.work.emplace(d.ioc.get_executor());
  d.listener->run();
  d.tick_time();
  d.tick_drain();
  for (int i = 0; i < cfg.io_threads; ++i) d.threads.emplace_back([&d] { d.ioc.run(); });
  const auto token = effective_token(cfg);
  logger("web")->info("dashboard on http://{}:{}/ (Foxglove WebSocket on the same port); tuning {}", cfg.bind,
                      d.listener->port(), token.empty() ? "disabled (no token)" : "needs the token");
}

void WebServer::stop() {
  auto& d = *impl_;
  if (!d.started || d.stopped) return;
  d.stopped = true;
  net::post(d.ioc, [&d] {
    d.listener->shutdown();
    d.time_timer.cancel();
    d.drain_timer.cancel();
    d.ctx->tracker.shutdown_all();
  });
  // Give clients a moment to receive their close frames, then end whatever is left.
  if (!d.ctx->tracker.wait_empty(std::chrono::seconds(2)))
    logger("web")->warn("{} connections did not close in time", d.ctx->tracker.size());
  d.work.reset();
  d.ioc.stop();
  for (auto& t : d.threads) t.join();
  d.threads.clear();
}

ChannelId WebServer::add_channel(const std::string& topic, const std::string& schema_name,
                                 const std::string& json_schema, ChannelOptions options) {
  return impl_->ctx->hub->add_channel(topic, schema_name, json_schema, options);
}

void WebServer::publish(ChannelId channel, Stamp t, std::string json_payload, std::string state) {
  impl_->ctx->hub->publish(channel, t, std::move(json_payload), std::move(state));
}

void WebServer::set_state_provider(std::function<nlohmann::json()> provider) {
  impl_->ctx->api->set_state_provider(std::move(provider));
}

Metrics& WebServer::metrics() { return impl_->ctx->metrics; }

std::uint16_t WebServer::port() const {
  return impl_->listener ? impl_->listener->port() : static_cast<std::uint16_t>(impl_->ctx->config.port);
}

std::size_t WebServer::client_count() const { return impl_->ctx->hub->peer_count(); }

}  // namespace fsd::web
