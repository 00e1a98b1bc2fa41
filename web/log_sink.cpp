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

class HandlerSink final : public spdlog::sinks::base_sink<std::mutex> {
 public:
  explicit HandlerSink(LogLineHandler handler) : handler_(std::move(handler)) {}

 protected:
  void sink_it_(const spdlog::details::log_msg& msg) override {
    handler_({to_foxglove(msg.level), std::string(msg.logger_name.begin(), msg.logger_name.end()),
              std::string(msg.payload.begin(), msg.payload.end())});
  }
  void flush_() override {}

 private:
  LogLineHandler handler_;
};

}  // namespace

std::shared_ptr<spdlog::sinks::sink> make_log_sink(LogLineHandler handler, spdlog::level::level_enum level) {
  auto sink = std::make_shared<HandlerSink>(std::move(handler));
  sink->set_level(level);
  return sink;
}

std::shared_ptr<spdlog::sinks::sink> make_log_sink(WebServer& server, ChannelId log_channel, const Clock& clock,
                                                   spdlog::level::level_enum level) {
  return make_log_sink(
      [&server, log_channel, &clock](LogLine l) {
        const Stamp t = clock.now();
        server.publish(log_channel, t, log_json(t, l.level, l.name, l.message));
      },
      level);
}

}  // namespace fsd::web
