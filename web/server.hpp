#pragma once
// The pit-lane web server (DESIGN.md §1, §6, §7): one port for the dashboard's files, a small JSON API,
// /healthz, /metrics and the Foxglove WebSocket protocol v1, so that our dashboard and Foxglove Studio both
// connect. It owns its I/O threads; publishers on other threads (the control thread among them) hand over
// telemetry without ever waiting for a client.
#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "common/params.hpp"
#include "common/time.hpp"
#include "web/config.hpp"
#include "web/hub.hpp"
#include "web/metrics.hpp"

namespace fsd {
class Clock;
}

namespace fsd::web {

class WebServer {
 public:
  // The token is effective_token(cfg). `params` and `clock` must outlive the server.
  WebServer(const WebConfig& cfg, ParamRegistry& params, Clock& clock);
  ~WebServer();  // stops
  WebServer(const WebServer&) = delete;
  WebServer& operator=(const WebServer&) = delete;

  // Binds and starts the I/O threads; throws std::runtime_error when the address cannot be bound.
  void start();
  // Closes every connection (WebSocket clients get a close frame), then joins the I/O threads. Idempotent.
  void stop();

  // Advertised to clients connected now and later. Allowed before and after start(); topics are unique.
  ChannelId add_channel(const std::string& topic, const std::string& schema_name, const std::string& json_schema,
                        ChannelOptions options = {});
  // Any thread; wait-free (a lock-free hand-over to the I/O thread, which fans out within ~2 ms): each
  // subscribed client gets the message in its bounded queue, and a client that reads too slowly loses its oldest
  // telemetry (counted in fsd_web_messages_dropped_total).
  // On a delta channel (ChannelOptions::delta) `state` is the whole state after this change.
  void publish(ChannelId channel, Stamp t, std::string json_payload, std::string state = {});
  // The body of /api/state; called on a web I/O thread, so it must be thread-safe.
  void set_state_provider(std::function<nlohmann::json()> provider);

  Metrics& metrics();
  std::uint16_t port() const;  // the bound port once started (useful with port 0)
  std::size_t client_count() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace fsd::web
