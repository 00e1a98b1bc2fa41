#include "control/tracking/contact_guard.hpp"

#include <algorithm>
#include <cmath>
#include <deque>

#include "common/car.hpp"
#include "control/planning/speed_profile.hpp"

namespace fsd {

GuardResult ContactGuard::check(const Path& path, PathFollower follower, const VehicleState& state,
                                const ControlCommand& command, const std::vector<Obstacle>& cones, const Body& body,
                                double wheelbase, double max_steer) const {
  GuardResult r;
  if (!config_.enabled || path.empty() || !(config_.dt > 0) || !(wheelbase > 0)) return r;
  const Vec2 at = state.pose.position();
  std::vector<Obstacle> near;
  std::vector<Obstacle> touching;  // already in contact: nothing to do about them now
  for (const auto& o : cones) {
    if ((o.p - at).norm() > config_.range) continue;
    (body_clearance(state.pose, o, body) < config_.margin ? touching : near).push_back(o);
  }
  double v = std::max(0.0, state.speed());
  double target = std::max(0.0, command.target_speed);
  if (near.empty() || std::max(v, target) < 0.05) return r;

  // The prediction: the follower steers the model; the wheels follow its commands after the delay at the rate.
  VehicleState s = state;
  double delta = std::isfinite(state.steering) ? state.steering : 0.0;
  // Steering commands in flight: (time they reach the wheels, angle); the wheels turn towards the newest arrived.
  std::deque<std::pair<double, double>> in_flight{{config_.steer_delay, command.steering}};
  double wheel_target = delta;
  const int steps = static_cast<int>(std::ceil(config_.horizon / config_.dt));
  double travelled = 0;
  for (int k = 1; k <= steps; ++k) {
    const double t = k * config_.dt;
    while (!in_flight.empty() && in_flight.front().first <= t + 1e-9) {
      wheel_target = in_flight.front().second;
      in_flight.pop_front();
    }
    const double step = config_.steer_rate * config_.dt;
    delta = std::clamp(delta + std::clamp(wheel_target - delta, -step, step), -max_steer, max_steer);
    v = std::max(0.0, v + std::clamp(target - v, -config_.decel * config_.dt, config_.accel * config_.dt));
    if (v < 0.05 && target < 0.05) return r;  // stopped short of everything
    // Understeer: the curvature the wheels give at this speed, κ from δ = atan(L·κ) + K·v²·κ (solved by iteration).
    double kappa = kinematic_curvature(delta, wheelbase);
    for (int it = 0; it < 3; ++it) kappa = kinematic_curvature(delta - config_.understeer * v * v * kappa, wheelbase);
    // The rear axle slips by the angle the follower expects (it steers the car's nose that much into the turn).
    const double slip = follower.expected_sideslip(v, kappa);
    const double yaw_mid = s.pose.yaw + 0.5 * v * kappa * config_.dt - slip;
    s.pose.x += v * config_.dt * std::cos(yaw_mid);
    s.pose.y += v * config_.dt * std::sin(yaw_mid);
    s.pose.yaw = wrap_angle(s.pose.yaw + v * kappa * config_.dt);
    s.steering = delta;
    s.stamp = state.stamp + t;
    travelled += v * config_.dt;
    r.predicted.push_back(s.pose);
    const PoseSweepResult hit = sweep_poses({s.pose}, near, body, config_.margin);
    if (hit.first_short >= 0) {
      r.contact = true;
      r.distance = travelled;
      r.cone = near[static_cast<std::size_t>(hit.obstacle)].p;
      r.speed_cap = stopping_speed(travelled, config_.decel, config_.latency);
      return r;
    }
    const FollowResult f = follower.follow(path, s, s.stamp, 1e9);
    if (f.ok) {
      in_flight.emplace_back(t + config_.steer_delay, f.command.steering);
      target = std::min(f.command.target_speed, command.target_speed);
    }
  }
  return r;
}

}  // namespace fsd
