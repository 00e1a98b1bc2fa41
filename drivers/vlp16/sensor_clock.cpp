#include "drivers/vlp16/sensor_clock.hpp"

#include <algorithm>

namespace fsd {

namespace {
constexpr std::int64_t kHalfHourUs = 1'800'000'000;
}  // namespace

Stamp SensorClock::packet_start(Stamp receive, std::uint32_t timestamp_us, double duration_us) {
  // Unwrap the hour: a timestamp far below the previous one is the next hour; a small step back is reordering.
  const std::int64_t step = std::int64_t{timestamp_us} - std::int64_t{last_timestamp_us_};
  if (have_offset_ && step < -kHalfHourUs) {
    hours_ += 3600.0;
    ++hour_wraps_;
  } else if (have_offset_ && step > kHalfHourUs && hours_ > 0) {
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
