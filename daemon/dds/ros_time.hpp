#pragma once
// The run's clock (a Stamp in seconds from the run's start, DESIGN.md §4) on the wire as ROS 2 time: seconds and
// nanoseconds since the Unix epoch, so that two processes (or two computers with synchronised clocks) read each
// other's stamps. Each process knows the epoch time of its run clock's zero; a stamp crosses as epoch + stamp.
#include <chrono>
#include <cmath>
#include <cstdint>

#include "common/time.hpp"

namespace fsd::dds {

struct RosTime {
  std::int32_t sec = 0;
  std::uint32_t nanosec = 0;
};

// The wall clock's seconds since the epoch now, minus the run clock's `run_now`: the epoch of the run's zero.
inline double run_epoch(Stamp run_now) {
  const auto wall = std::chrono::system_clock::now().time_since_epoch();
  return std::chrono::duration<double>(wall).count() - run_now;
}

inline RosTime to_ros_time(double epoch_seconds) {
  double whole = std::floor(epoch_seconds);
  auto ns = static_cast<std::int64_t>(std::llround((epoch_seconds - whole) * 1e9));
  if (ns >= 1000000000) {
    whole += 1;
    ns -= 1000000000;
  }
  return {static_cast<std::int32_t>(whole), static_cast<std::uint32_t>(ns)};
}

inline double from_ros_time(RosTime t) { return static_cast<double>(t.sec) + 1e-9 * static_cast<double>(t.nanosec); }

}  // namespace fsd::dds
