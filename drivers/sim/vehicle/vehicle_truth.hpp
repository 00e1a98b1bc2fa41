#pragma once
// The virtual car's true motion state: what the vehicle model integrates, what the sensor models sample and
// what the scorecard compares the stack against.
#include <array>

#include "common/geometry.hpp"
#include "common/time.hpp"

namespace fsd::sim {

struct VehicleTruth {
  Stamp t = 0;
  Pose2 pose;             // rear-axle centre on the ground, map frame (local ENU at the start)
  double vx = 0, vy = 0;  // body-frame velocity of the centre of gravity, m/s
  double yaw_rate = 0;    // rad/s
  double ax = 0, ay = 0;  // body-frame acceleration at the CoG as an IMU measures it (includes centripetal), m/s²
  double roll = 0,
         pitch =
             0;  // body attitude relative to the ground from load transfer, rad (roll right-down +, pitch nose-down +)
  double steering = 0;                   // actual front wheel angle after the actuator, rad, left positive
  std::array<double, 4> wheel_speeds{};  // wheel circumferential speeds FL, FR, RL, RR, m/s
  double motor_torque = 0;               // at the wheels, N·m
  double brake_force = 0;                // total longitudinal brake force, N
  double distance = 0;                   // odometer, m

  double speed() const;
  double sideslip() const;  // β at the CoG, 0 below walking speed
  // 3D pose of the body frame (rear-axle centre, z up) including roll and pitch, for mounting sensors.
  Pose3 body_pose3() const;
};

}  // namespace fsd::sim
