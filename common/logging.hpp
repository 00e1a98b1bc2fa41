#pragma once
// Logging through spdlog. One call at start-up sets level and format; components then use spdlog's free
// functions (spdlog::info, ...) or a named logger from logger().
#include <memory>
#include <string>

#include <spdlog/spdlog.h>

namespace fsd {

// level: trace, debug, info, warn, error, critical, off. Throws std::invalid_argument on an unknown level.
void init_logging(const std::string& level);

// A logger named after a component ("vcu", "sim", ...), sharing the default sinks.
std::shared_ptr<spdlog::logger> logger(const std::string& component);

}  // namespace fsd
