#include "drivers/sim/vehicle/truth_history.hpp"

#include <algorithm>

#include "common/geometry.hpp"

namespace fsd::sim {

VehicleTruth interpolate(const VehicleTruth& a, const VehicleTruth& b, Stamp t) {
  if (b.t <= a.t) return b;
  const double w = std::clamp((t - a.t) / (b.t - a.t), 0.0, 1.0);
  auto lerp = [w](double x, double y) { return x + w * (y - x); };
  VehicleTruth r = b;
  r.t = t;
  r.pose = {lerp(a.pose.x, b.pose.x), lerp(a.pose.y, b.pose.y),
            wrap_angle(a.pose.yaw + w * wrap_angle(b.pose.yaw - a.pose.yaw))};
  r.vx = lerp(a.vx, b.vx);
  r.vy = lerp(a.vy, b.vy);
  r.yaw_rate = lerp(a.yaw_rate, b.yaw_rate);
  r.ax = lerp(a.ax, b.ax);
  r.ay = lerp(a.ay, b.ay);
  r.roll = lerp(a.roll, b.roll);
  r.pitch = lerp(a.pitch, b.pitch);
  r.steering = lerp(a.steering, b.steering);
  r.distance = lerp(a.distance, b.distance);
  return r;
}

void TruthHistory::push(const VehicleTruth& step) {
  steps_.push_back(step);
  if (steps_.size() > capacity_) steps_.pop_front();
}

VehicleTruth TruthHistory::at(Stamp t) const {
  // The first step at or after t, and the one before it.
  const auto after =
      std::lower_bound(steps_.begin(), steps_.end(), t, [](const VehicleTruth& s, Stamp at) { return s.t < at; });
  if (after == steps_.end()) return steps_.back();
  if (after == steps_.begin() || after->t <= t) return *after;
  return interpolate(*(after - 1), *after, t);
}

}  // namespace fsd::sim
