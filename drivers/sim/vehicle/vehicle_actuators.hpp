#pragma once
// What sits between the autonomy's command and the virtual car's wheels: the steering actuator (dead time, rate
// and angle limits) and the VCU's speed controller (target speed → drive force or brake force).
#include <array>
#include <cstddef>

#include "common/time.hpp"
#include "drivers/sim/vehicle/vehicle_params.hpp"

namespace fsd::sim {

// What the VCU receives from the autonomy and its own AS state machine.
struct ActuatorCommand {
  double steering = 0;         // requested front wheel angle, rad, left positive
  double target_speed = 0;     // m/s: the VCU's own speed controller turns it into motor torque / brake
  bool max_brake = false;      // controlled stop: full service braking
  bool ebs = false;            // emergency brake system: full braking, motor torque off
  bool drive_enabled = false;  // motor torque allowed only when true (AS Driving)
};

// Front wheel angle actuator: the request is clamped to the angle limit, delayed by the dead time, and the wheel
// angle follows it at most at the rate limit. Fixed storage: no allocation while stepping.
class SteeringActuator {
 public:
  explicit SteeringActuator(const VehicleParams& p);
  void reset(double angle = 0.0);
  // Takes the request made at time t and moves the wheel angle over [t, t + dt]; returns the new angle.
  double step(Stamp t, double dt, double requested);
  double angle() const { return angle_; }

 private:
  struct Sample {
    Stamp t = 0;
    double angle = 0;
  };
  // Requests in flight through the dead time; only changes are stored. When full (a dead time far longer than
  // the command rate), the oldest request takes effect early.
  static constexpr std::size_t kCapacity = 1024;
  std::array<Sample, kCapacity> queue_{};
  std::size_t head_ = 0, size_ = 0;
  double dead_time_, max_rate_, max_angle_;
  double last_request_ = 0;  // newest request, to skip unchanged ones
  double effective_ = 0;     // request that has come out of the dead time
  double angle_ = 0;
};

// The longitudinal request the VCU makes of the powertrain, as forces at the ground.
struct LongitudinalRequest {
  double drive = 0;  // N at the rear contact patches, within the motor limits
  double brake = 0;  // N, all wheels together
};

// The VCU's speed controller: PI on the speed error plus drag and rolling-resistance feed-forward. Positive
// force goes to the motor (only with drive enabled), negative to the brakes. The integral only acts near the
// target and stops while the request is cut by the motor or the tyres (traction control, ABS), so a launch or a
// hard stop does not wind it up. With target 0 it brakes to a stop and holds the car on the brakes. Without
// drive enabled the controller is off and the car coasts unless max_brake or ebs brakes it fully.
class SpeedController {
 public:
  explicit SpeedController(const VehicleParams& p) : p_(p) {}
  void reset() { integral_ = 0; }
  // `grip`: what the tyres can transmit now (traction control's and ABS's estimate), N at the ground.
  LongitudinalRequest step(double dt, const ActuatorCommand& cmd, double speed, const LongitudinalRequest& grip);

 private:
  VehicleParams p_;
  double integral_ = 0;  // ∫ speed error dt, m
};

}  // namespace fsd::sim
