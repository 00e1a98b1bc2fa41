#include "daemon/stack/raw_frame.hpp"

#include <array>

namespace fsd {

namespace {
constexpr std::array<std::string_view, kRawChannels> kNames{
    "vlp16_data", "vlp16_position", "nmea",        "camera",     "vcu_rx",
    "vcu_tx",     "truth_state",    "truth_cones", "truth_scan", "truth_lidar_returns"};
}

std::string_view to_string(RawChannel c) {
  const auto i = static_cast<std::size_t>(c);
  return i < kNames.size() ? kNames[i] : "unknown";
}

std::optional<RawChannel> raw_channel_from_string(std::string_view s) {
  for (std::size_t i = 0; i < kNames.size(); ++i)
    if (kNames[i] == s) return static_cast<RawChannel>(i);
  return std::nullopt;
}

}  // namespace fsd
