#pragma once
// The last few physics steps of the virtual car, for the sensors to pose their samples at any time in between. A
// VLP-16 packet lasts 1.33 ms and a step 2.5 ms, so a packet emitted after a step may hold firings from the step
// before it: posed from the last two steps only, those would take that step's end pose (up to 1.3 ms stale, 2.6 cm
// at 20 m/s). Bounded: the oldest step is dropped past `capacity`.
#include <cstddef>
#include <deque>

#include "drivers/sim/vehicle/vehicle_truth.hpp"

namespace fsd::sim {

// The truth at `t` between two steps (a.t ≤ t ≤ b.t): linear in every field, the yaw along the shorter way round;
// the rest (wheel speeds, torques) are b's.
VehicleTruth interpolate(const VehicleTruth& a, const VehicleTruth& b, Stamp t);

class TruthHistory {
 public:
  explicit TruthHistory(std::size_t capacity = 16) : capacity_(capacity < 2 ? 2 : capacity) {}
  // A step, later than the ones before.
  void push(const VehicleTruth& step);
  // Interpolated between the steps around t; the oldest kept before them, the newest after. Needs one step.
  VehicleTruth at(Stamp t) const;
  std::size_t size() const { return steps_.size(); }

 private:
  std::size_t capacity_;
  std::deque<VehicleTruth> steps_;  // oldest first
};

}  // namespace fsd::sim
