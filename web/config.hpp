#pragma once
// Configuration of the pit-lane web server (DESIGN.md §1, §6, §7): one port for HTTP and the Foxglove WebSocket.
#include <string>

#include "common/config.hpp"

namespace fsd::web {

struct WebConfig {
  std::string bind = "0.0.0.0";  // the car's Wi-Fi; 127.0.0.1 keeps it on the machine
  int port = 8080;               // 0 = any free port (tests)
  std::string web_root = "web/dashboard/dist";
  std::string token;  // empty = tuning disabled; FSD_WEB_TOKEN overrides
  int io_threads = 1;
  int max_clients = 32;              // WebSocket clients at once
  int max_frame_bytes = 65536;       // largest accepted incoming WebSocket message / HTTP body
  int client_send_queue = 256;       // telemetry messages queued per client before the oldest is dropped
  int max_incoming_msgs_per_s = 50;  // per client
  std::string allowed_origins;       // comma-separated; empty = same host only; "*" = any
  int idle_timeout_s = 30;
};

const ConfigSection<WebConfig>& web_section();

// The token in force: FSD_WEB_TOKEN from the environment when set (even empty), else the configured one.
std::string effective_token(const WebConfig& cfg);

}  // namespace fsd::web
