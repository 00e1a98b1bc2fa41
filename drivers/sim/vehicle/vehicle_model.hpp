#pragma once
// Vehicle dynamics of the virtual car (issue 3): a dynamic single-track model with Pacejka lateral tyre forces,
// axle loads from static weight, longitudinal load transfer and downforce, friction circles, rear-wheel drive
// with torque and power limits, brakes, aero drag and rolling resistance; blended into a kinematic single-track
// model at low speed so it is well-behaved from standstill. The steering actuator and the VCU's speed controller
// sit in front of it. Body roll and pitch follow the (lagged) accelerations through roll and pitch stiffness.
// Integration: RK4 at the caller's fixed step (split into sub-steps of at most 5 ms); at low speed the brakes
// and rolling resistance act as dry friction, applied as an impulse after the RK4 step so that the car stops
// exactly and stands still. Tyres run at their friction limit without wheel spin or lock-up (traction control
// and ABS), so the wheel speeds are the contact patches' rolling speeds. Deterministic, no allocation in step().
#include <array>
#include <cstdint>

#include "common/geometry.hpp"
#include "common/time.hpp"
#include "drivers/sim/vehicle/vehicle_actuators.hpp"
#include "drivers/sim/vehicle/vehicle_params.hpp"
#include "drivers/sim/vehicle/vehicle_truth.hpp"

namespace fsd::sim {

class VehicleModel {
 public:
  // Throws std::invalid_argument naming the problem when validate(p) fails.
  explicit VehicleModel(const VehicleParams& p);

  // Places the car at rest (or rolling straight at `speed` ≥ 0) with the wheels straight and the VCU reset.
  void reset(const Pose2& rear_axle_pose, double speed = 0.0, Stamp t = 0.0);
  // Advances by dt seconds with the command held. A dt that is not in (0, 1] s is rejected and counted.
  void step(double dt, const ActuatorCommand& cmd);

  const VehicleTruth& truth() const { return truth_; }
  const VehicleParams& params() const { return p_; }
  std::uint64_t rejected_steps() const { return rejected_steps_; }
  // Corners of the body outline on the ground, map frame, counter-clockwise from rear right:
  // rear right, front right, front left, rear left.
  std::array<Vec2, 4> footprint() const;

  // Integrated state: rear-axle pose, CoG velocities in the body frame, odometer.
  struct State {
    double x = 0, y = 0, yaw = 0;
    double vx = 0, vy = 0, yaw_rate = 0;
    double distance = 0;
  };

 private:
  void substep(double dt, const ActuatorCommand& cmd);
  void update_truth(double drive_applied, double brake_applied, double ax, double ay);

  VehicleParams p_;
  SteeringActuator steering_;
  SpeedController vcu_;
  State s_;
  Stamp t_ = 0;
  double ax_lagged_ = 0, ay_lagged_ = 0;  // accelerations as the suspension has followed them
  VehicleTruth truth_;
  std::uint64_t rejected_steps_ = 0;
};

}  // namespace fsd::sim
