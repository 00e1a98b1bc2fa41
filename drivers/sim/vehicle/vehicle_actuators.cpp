#include "drivers/sim/vehicle/vehicle_actuators.hpp"

#include <algorithm>
#include <cmath>

#include "drivers/sim/vehicle/vehicle_forces.hpp"

namespace fsd::sim {

SteeringActuator::SteeringActuator(const VehicleParams& p)
    : dead_time_(p.steer_dead_time), max_rate_(p.steer_max_rate), max_angle_(p.steer_max_angle) {}

void SteeringActuator::reset(double angle) {
  head_ = size_ = 0;
  last_request_ = effective_ = angle_ = std::clamp(angle, -max_angle_, max_angle_);
}

double SteeringActuator::step(Stamp t, double dt, double requested) {
  // A request that is not a number keeps the previous one.
  const double req = std::isfinite(requested) ? std::clamp(requested, -max_angle_, max_angle_) : last_request_;
  if (req != last_request_) {
    if (size_ == kCapacity) {  // overflow: the oldest request takes effect now
      effective_ = queue_[head_].angle;
      head_ = (head_ + 1) % kCapacity;
      --size_;
    }
    queue_[(head_ + size_) % kCapacity] = {t, req};
    ++size_;
    last_request_ = req;
  }
  // Requests whose dead time has passed by the start of this step act over it. The small margin keeps a
  // dead time that is a whole number of steps from slipping by one step through rounding of t.
  while (size_ > 0 && queue_[head_].t + dead_time_ <= t + 1e-9) {
    effective_ = queue_[head_].angle;
    head_ = (head_ + 1) % kCapacity;
    --size_;
  }
  const double max_delta = max_rate_ * dt;
  angle_ += std::clamp(effective_ - angle_, -max_delta, max_delta);
  return angle_;
}

LongitudinalRequest SpeedController::step(double dt, const ActuatorCommand& cmd, double speed,
                                          const LongitudinalRequest& grip) {
  if (cmd.ebs || cmd.max_brake) {
    reset();
    return {0.0, p_.brake_max_force};
  }
  if (!cmd.drive_enabled) {
    reset();
    return {};
  }
  constexpr double kStopTarget = 0.01;  // m/s: a target below this means "stop"
  const double target = std::isfinite(cmd.target_speed) ? std::clamp(cmd.target_speed, 0.0, p_.max_speed) : 0.0;
  if (target < kStopTarget && speed < p_.stop_hold_speed) {
    reset();
    return {0.0, p_.brake_max_force};
  }
  const double error = target - speed;
  const double accel = p_.speed_kp * error + p_.speed_ki * integral_;
  const double force = p_.mass * accel + drag_force(p_, speed) + rolling_resistance_force(p_);
  const double drive_max = std::min(drive_force_limit(p_, speed), grip.drive);
  const double brake_max = std::min(p_.brake_max_force, grip.brake);
  const bool saturated = force > drive_max || force < -brake_max;
  if (!saturated && std::abs(error) < p_.speed_integral_band && p_.speed_ki > 0) {
    const double limit = p_.speed_integral_limit / p_.speed_ki;
    integral_ = std::clamp(integral_ + error * dt, -limit, limit);
  }
  if (force >= 0) return {std::min(force, drive_max), 0.0};
  return {0.0, std::min(-force, brake_max)};
}

}  // namespace fsd::sim
