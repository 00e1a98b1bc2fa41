#pragma once
// Maps the sensor's firing times (µs past the hour) onto the stack's clock (DESIGN.md §4).
//
// The caller gives each packet's receive time on the stack clock (host time on the car, simulated time in sim and
// replay). The sensor sends a packet right after its last firing, so
//     receive = sensor_end + offset + latency,  latency >= 0,  sensor_end = timestamp + packet duration.
// The offset is estimated as the running minimum of (receive - sensor_end): network and scheduling delays only
// ever add, so the minimum rejects their jitter and every firing gets a time that is exact relative to the
// others. The minimum may rise by `max_drift` × elapsed time (sensor crystal vs host clock), and is reset when
// the candidate stays more than `max_jump` above it (sensor reboot, PPS lock moving its clock). With zero latency
// (lockstep simulation) the mapping is exact: firing time = receive - duration + firing offset.
#include <cstdint>

#include "common/time.hpp"

namespace fsd {

class SensorClock {
 public:
  struct Params {
    double max_drift = 2e-4;     // s/s the estimate may rise without evidence (crystal tolerance + margin)
    Duration max_jump = 0.05;    // s above the estimate that counts as a clock step
    int jump_confirmations = 8;  // consecutive packets above max_jump before the estimate resets
  };
  SensorClock() = default;
  explicit SensorClock(Params p) : p_(p) {}

  // Stack time of a packet's first firing. `timestamp_us` is the packet's µs past the hour; `duration_us` the
  // time its firings cover.
  Stamp packet_start(Stamp receive, std::uint32_t timestamp_us, double duration_us);

  std::uint64_t resets() const { return resets_; }  // offset re-estimated from scratch (first packet included)
  std::uint64_t hour_wraps() const { return hour_wraps_; }

 private:
  Params p_;
  bool have_offset_ = false;
  double offset_ = 0;  // stack time − sensor time, s
  Stamp last_receive_ = 0;
  std::uint32_t last_timestamp_us_ = 0;
  double hours_ = 0;  // completed hours of sensor time, s
  int above_ = 0;
  std::uint64_t resets_ = 0, hour_wraps_ = 0;
};

}  // namespace fsd
