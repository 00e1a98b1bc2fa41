#pragma once
// The test's own car: a kinematic bicycle with a pure delay on the commands, a first-order steering actuator
// with a rate limit, and a speed loop limited by traction and brakes. Written from the textbook equations,
// independently of the follower's predictor.
#include <algorithm>
#include <cmath>
#include <deque>

#include "common/types.hpp"

namespace fsd::test {

struct BicycleSim {
  double wheelbase = 1.53;
  double delay = 0.06;              // s, command to actuator
  double steer_tau = 0.05;          // s, first-order steering response
  double steer_rate = 1.5;          // rad/s
  double max_steer = 0.5;           // rad
  double accel = 5.0, brake = 8.0;  // m/s²
  double speed_gain = 3.0;          // 1/s, speed loop
  double dt = 0.005;                // s, integration step

  double t = 0;
  Pose2 pose;
  double v = 0, delta = 0, yaw_rate = 0, ax = 0;
  std::deque<std::pair<double, ControlCommand>> queue;  // (time it acts, command)
  ControlCommand active;

  void command(const ControlCommand& c) { queue.emplace_back(t + delay, c); }

  // Advances by `duration`, step by step.
  void run(double duration) {
    const int steps = static_cast<int>(std::round(duration / dt));
    for (int i = 0; i < steps; ++i) step();
  }

  void step() {
    while (!queue.empty() && queue.front().first <= t + 1e-12) {
      active = queue.front().second;
      queue.pop_front();
    }
    const double target_delta = std::clamp(active.steering, -max_steer, max_steer);
    const double ddelta = std::clamp((target_delta - delta) / steer_tau, -steer_rate, steer_rate);
    delta += ddelta * dt;
    // Speed loop; a zero target near standstill holds the car with the brakes (no creeping).
    const bool hold = active.target_speed <= 0 && v < 0.5;
    const double want = active.brake_hard || hold ? -brake : speed_gain * (active.target_speed - v);
    ax = std::clamp(want, -brake, accel);
    if (v <= 0 && ax < 0) ax = 0;
    yaw_rate = v * std::tan(delta) / wheelbase;
    pose.x += v * std::cos(pose.yaw) * dt;
    pose.y += v * std::sin(pose.yaw) * dt;
    pose.yaw = wrap_angle(pose.yaw + yaw_rate * dt);
    v = std::max(0.0, v + ax * dt);
    t += dt;
  }

  VehicleState state() const {
    VehicleState s;
    s.stamp = t;
    s.pose = pose;
    s.vx = v;
    s.yaw_rate = yaw_rate;
    s.ax = ax;
    s.ay = v * yaw_rate;
    s.steering = delta;
    return s;
  }
};

}  // namespace fsd::test
