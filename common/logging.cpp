#include "common/logging.hpp"

#include <mutex>
#include <stdexcept>

#include <spdlog/sinks/stdout_color_sinks.h>

namespace fsd {

namespace {
std::mutex g_mutex;
}

void init_logging(const std::string& level) {
  const auto lvl = spdlog::level::from_str(level);
  if (lvl == spdlog::level::off && level != "off")
    throw std::invalid_argument("unknown log level '" + level + "' (trace, debug, info, warn, error, critical, off)");
  std::lock_guard lock(g_mutex);
  // Logs go to stderr so that stdout stays clean for data output (lidar-dump, reports).
  auto sink = std::make_shared<spdlog::sinks::stderr_color_sink_mt>();
  auto root = std::make_shared<spdlog::logger>("fsd", sink);
  root->set_level(lvl);
  root->set_pattern("%H:%M:%S.%e %^%-5l%$ [%n] %v");
  spdlog::set_default_logger(root);
  spdlog::apply_all([&](const std::shared_ptr<spdlog::logger>& l) { l->set_level(lvl); });
}

std::shared_ptr<spdlog::logger> logger(const std::string& component) {
  std::lock_guard lock(g_mutex);
  if (auto existing = spdlog::get(component)) return existing;
  auto root = spdlog::default_logger();
  auto l = std::make_shared<spdlog::logger>(component, root->sinks().begin(), root->sinks().end());
  l->set_level(root->level());
  l->set_pattern("%H:%M:%S.%e %^%-5l%$ [%n] %v");
  spdlog::register_logger(l);
  return l;
}

}  // namespace fsd
