#include "daemon/service/journal_log.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <mutex>
#include <string>

#include <spdlog/sinks/base_sink.h>
#include <spdlog/spdlog.h>

namespace fsd {

namespace {

// JOURNAL_STREAM is "<device>:<inode>" of the stream systemd connected; it is ours only if fd 2 is that stream.
bool stderr_is_journal() {
  const char* js = std::getenv("JOURNAL_STREAM");
  if (!js) return false;
  unsigned long long dev = 0, ino = 0;
  if (std::sscanf(js, "%llu:%llu", &dev, &ino) != 2) return false;
  struct stat st {};
  if (fstat(STDERR_FILENO, &st) != 0) return false;
  return static_cast<unsigned long long>(st.st_dev) == dev && static_cast<unsigned long long>(st.st_ino) == ino;
}

int priority(spdlog::level::level_enum l) {
  switch (l) {
    case spdlog::level::critical:
      return 2;  // LOG_CRIT
    case spdlog::level::err:
      return 3;
    case spdlog::level::warn:
      return 4;
    case spdlog::level::info:
      return 6;
    default:
      return 7;  // debug, trace
  }
}

class JournalStreamSink final : public spdlog::sinks::base_sink<std::mutex> {
 protected:
  void sink_it_(const spdlog::details::log_msg& msg) override {
    spdlog::memory_buf_t text;
    formatter_->format(msg, text);
    char prefix[8];
    const int n = std::snprintf(prefix, sizeof prefix, "<%d>", priority(msg.level));
    std::fwrite(prefix, 1, static_cast<std::size_t>(n), stderr);
    std::fwrite(text.data(), 1, text.size(), stderr);
  }
  void flush_() override { std::fflush(stderr); }
};

}  // namespace

bool log_to_journal_if_there() {
  if (!stderr_is_journal()) return false;
  auto sink = std::make_shared<JournalStreamSink>();
  sink->set_pattern("[%n] %v");  // the journal has the time, the unit and the priority
  spdlog::default_logger()->sinks() = {sink};
  spdlog::apply_all([&](const std::shared_ptr<spdlog::logger>& l) { l->sinks() = {sink}; });
  spdlog::default_logger()->flush_on(spdlog::level::warn);
  return true;
}

}  // namespace fsd
