#include "drivers/sim/vehicle/vehicle_forces.hpp"

#include <algorithm>
#include <cmath>

namespace fsd::sim {

namespace {
double dynamic_pressure(const VehicleParams& p, double speed) { return 0.5 * p.air_density * speed * speed; }
}  // namespace

double drag_force(const VehicleParams& p, double speed) {
  return std::copysign(dynamic_pressure(p, speed) * p.drag_area, speed);
}

double downforce(const VehicleParams& p, double speed) { return dynamic_pressure(p, speed) * p.downforce_area; }

double rolling_resistance_force(const VehicleParams& p) { return p.rolling_resistance * p.mass * kGravity; }

AxleLoads axle_loads(const VehicleParams& p, double speed, double ax) {
  const double weight = p.mass * kGravity;
  const double transfer = p.mass * ax * p.cog_height / p.wheelbase;
  const double down = downforce(p, speed);
  const double front = weight * p.cog_to_rear_axle / p.wheelbase - transfer + p.aero_front_share * down;
  const double rear = weight * p.cog_to_front_axle() / p.wheelbase + transfer + (1.0 - p.aero_front_share) * down;
  return {std::max(front, 0.0), std::max(rear, 0.0)};
}

double drive_force_limit(const VehicleParams& p, double speed) {
  // Below 0.1 m/s the power limit is irrelevant (torque binds); the floor avoids dividing by zero.
  const double v = std::max(std::abs(speed), 0.1);
  const double torque_limit = p.motor_max_torque / p.wheel_radius;
  const double power_limit = p.drivetrain_efficiency * p.motor_max_power / v;
  const double fade = std::clamp((p.max_speed - speed) / kMaxSpeedFadeBand, 0.0, 1.0);
  return std::min(torque_limit, power_limit) * fade;
}

}  // namespace fsd::sim
