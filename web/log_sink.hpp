#pragma once
// An spdlog sink that publishes log lines on the /log channel (foxglove.Log), so the dashboard and Foxglove
// Studio show them. Publishing never blocks, so logging from the control thread stays cheap.
#include <functional>
#include <memory>
#include <string>

#include <spdlog/sinks/sink.h>

#include "web/channels.hpp"
#include "web/hub.hpp"

namespace fsd {
class Clock;
}

namespace fsd::web {

class WebServer;

// A log line as a sink hands it on.
struct LogLine {
  LogLevel level = LogLevel::Info;
  std::string name;  // the logger's
  std::string message;
};
using LogLineHandler = std::function<void(LogLine)>;

// A sink that hands every line at `level` and above to `handler` (on the logging thread: it must not block).
std::shared_ptr<spdlog::sinks::sink> make_log_sink(LogLineHandler handler,
                                                   spdlog::level::level_enum level = spdlog::level::info);

// The sink keeps references to `server` and `clock`: remove it from the loggers before the server goes away.
// Lines below `level` (default info) are not published.
std::shared_ptr<spdlog::sinks::sink> make_log_sink(WebServer& server, ChannelId log_channel, const Clock& clock,
                                                   spdlog::level::level_enum level = spdlog::level::info);

}  // namespace fsd::web
