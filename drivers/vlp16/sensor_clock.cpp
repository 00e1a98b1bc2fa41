#include "drivers/vlp16/sensor_clock.hpp"

#include <algorithm>

namespace fsd {

namespace {
constexpr std::uint32_t kHourUs = 3'600'000'000U;
constexpr std::uint32_t kHalfHourUs = kHourUs / 2;
}  // namespace

Stamp SensorClock::packet_start(Stamp receive, std::uint32_t timestamp_us, double duration_us) {
  // Unwrap the hour: a timestamp far below the previous one is the next hour; a small step back is reordering.
  if (have_offset_ && timestamp_us + kHalfHourUs < last_timestamp_us_) {
    hours_ += 3600.0;
    ++hour_wraps_;
  } else if (have_offset_ && timestamp_us > last_timestamp_us_ + kHalfHourUs && hours_ > 0) {
    hours_ -= 3600.0;  // a late packet from before the wrap
  }
  const double sensor_start = hours_ + timestamp_us * 1e-6;
  const double candidate = receive - (sensor_start + duration_us * 1e-6);

  if (!have_offset_) {
    offset_ = candidate;
    have_offset_ = true;
    last_receive_ = receive;
    ++resets_;
  } else {
    offset_ += p_.max_drift * std::max(0.0, receive - last_receive_);
    if (candidate > offset_ + p_.max_jump) {
      if (++above_ >= p_.jump_confirmations) {
        offset_ = candidate;
        above_ = 0;
        ++resets_;
      }
    } else {
      above_ = 0;
      offset_ = std::min(offset_, candidate);
    }
  }
  last_receive_ = std::max(last_receive_, receive);
  last_timestamp_us_ = timestamp_us;
  return sensor_start + offset_;
}

}  // namespace fsd
