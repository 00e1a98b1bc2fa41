#include "web/log_sink.hpp"

#include <mutex>

#include <spdlog/sinks/base_sink.h>

#include "common/clock.hpp"
#include "web/channels.hpp"
#include "web/server.hpp"

namespace fsd::web {

namespace {

LogLevel to_foxglove(spdlog::level::level_enum l) {
  switch (l) {
    case spdlog::level::trace:
    case spdlog::level::debug:
      return LogLevel::Debug;
    case spdlog::level::info:
      return LogLevel::Info;
    case spdlog::level::warn:
      return LogLevel::Warning;
    case spdlog::level::err:
      return LogLevel::Error;
    case spdlog::level::critical:
      return LogLevel::Fatal;
    default:
      return LogLevel::Unknown;
  }
}

class WebLogSink final : public spdlog::sinks::base_sink<std::mutex> {
 public:
  WebLogSink(WebServer& server, ChannelId channel, const Clock& clock)
      : server_(server), channel_(channel), clock_(clock) {}

 protected:
  void sink_it_(const spdlog::details::log_msg& msg) override {
    const Stamp t = clock_.now();
    server_.publish(channel_, t,
                    log_json(t, to_foxglove(msg.level), std::string(msg.logger_name.begin(), msg.logger_name.end()),
                             std::string(msg.payload.begin(), msg.payload.end())));
  }
  void flush_() override {}

 private:
  WebServer& server_;
  ChannelId channel_;
  const Clock& clock_;
};

}  // namespace

std::shared_ptr<spdlog::sinks::sink> make_log_sink(WebServer& server, ChannelId log_channel, const Clock& clock,
                                                   spdlog::level::level_enum level) {
  auto sink = std::make_shared<WebLogSink>(server, log_channel, clock);
  sink->set_level(level);
  return sink;
}

}  // namespace fsd::web
