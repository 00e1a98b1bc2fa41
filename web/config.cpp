#include "web/config.hpp"

#include <cstdlib>

namespace fsd::web {

const ConfigSection<WebConfig>& web_section() {
  static const auto s =
      ConfigSection<WebConfig>("web")
          .string("bind", &WebConfig::bind, {}, "Address the dashboard server listens on (0.0.0.0 = every interface).")
          .integer("port", &WebConfig::port, 0, 65535, "",
                   "TCP port of the dashboard: HTTP and Foxglove WebSocket (0 = any free port).")
          .string("web_root", &WebConfig::web_root, {},
                  "Folder of the built dashboard; a relative path is tried from the working directory, then from the "
                  "source tree above the fsd binary (build/daemon/fsd).")
          .string("token", &WebConfig::token, {},
                  "Bearer token that authorises parameter changes; empty disables tuning. The environment variable "
                  "FSD_WEB_TOKEN overrides it.")
          .integer("io_threads", &WebConfig::io_threads, 1, 2, "threads", "I/O threads of the web server.")
          .integer("max_clients", &WebConfig::max_clients, 1, 256, "clients",
                   "WebSocket clients connected at once; more are refused with 503.")
          .integer("max_frame_bytes", &WebConfig::max_frame_bytes, 1024, 16 * 1024 * 1024, "bytes",
                   "Largest incoming WebSocket message or HTTP request body; larger ones are refused.")
          .integer("client_send_queue", &WebConfig::client_send_queue, 4, 65536, "messages",
                   "Telemetry messages queued per client; a client that reads slower loses the oldest.")
          .integer("max_incoming_msgs_per_s", &WebConfig::max_incoming_msgs_per_s, 1, 10000, "1/s",
                   "Messages a WebSocket client may send per second; the excess is refused.")
          .string("allowed_origins", &WebConfig::allowed_origins, {},
                  "Comma-separated browser origins allowed to connect (e.g. https://app.foxglove.dev); empty = the "
                  "server's own host only; * = any.")
          .integer("idle_timeout_s", &WebConfig::idle_timeout_s, 1, 3600, "s",
                   "A connection that sends nothing (not even a pong to the server's pings) for this long is closed.");
  return s;
}

std::string effective_token(const WebConfig& cfg) {
  if (const char* env = std::getenv("FSD_WEB_TOKEN")) return env;
  return cfg.token;
}

}  // namespace fsd::web
