#include "drivers/sim/vehicle/vehicle_params.hpp"

#include <cmath>

namespace fsd::sim {

const ConfigSection<VehicleParams>& vehicle_section() {
  using P = VehicleParams;
  static const auto s =
      ConfigSection<P>("sim.vehicle")
          .number("yaw_inertia", &P::yaw_inertia, 20.0, 500.0, "kg·m²", "Yaw moment of inertia about the CoG.")
          .number("track_width", &P::track_width, 0.8, 1.6, "m", "Distance between the wheel centres of one axle.")
          .number("cog_height", &P::cog_height, 0.1, 0.6, "m", "Height of the centre of gravity above the ground.")
          .number("cog_to_rear_axle", &P::cog_to_rear_axle, 0.3, 1.5, "m",
                  "Longitudinal distance from the rear axle forward to the CoG.")
          .number("wheel_radius", &P::wheel_radius, 0.15, 0.35, "m", "Loaded rolling radius of the wheels.")
          .number("mu", &P::mu, 0.2, 2.5, "", "Tyre-road friction coefficient (peak of the magic formula).")
          .number("tyre_front_b", &P::tyre_front_b, 1.0, 40.0, "1/rad", "Pacejka stiffness factor B, front axle.")
          .number("tyre_front_c", &P::tyre_front_c, 0.5, 2.0, "", "Pacejka shape factor C, front axle.")
          .number("tyre_front_e", &P::tyre_front_e, -2.0, 1.0, "", "Pacejka curvature factor E, front axle.")
          .number("tyre_rear_b", &P::tyre_rear_b, 1.0, 40.0, "1/rad", "Pacejka stiffness factor B, rear axle.")
          .number("tyre_rear_c", &P::tyre_rear_c, 0.5, 2.0, "", "Pacejka shape factor C, rear axle.")
          .number("tyre_rear_e", &P::tyre_rear_e, -2.0, 1.0, "", "Pacejka curvature factor E, rear axle.")
          .number("rolling_resistance", &P::rolling_resistance, 0.0, 0.1, "",
                  "Rolling resistance coefficient, times the static weight.")
          .number("motor_max_torque", &P::motor_max_torque, 0.0, 3000.0, "N·m",
                  "Largest drive torque at the rear wheels, both together.")
          .number("motor_max_power", &P::motor_max_power, 1000.0, 200000.0, "W",
                  "Largest power the motors draw (rules: 80 kW from the accumulator).")
          .number("drivetrain_efficiency", &P::drivetrain_efficiency, 0.5, 1.0, "",
                  "Share of the motor power that reaches the wheels.")
          .number("max_speed", &P::max_speed, 5.0, 60.0, "m/s",
                  "Motor speed limit as vehicle speed; the drive torque fades to zero over the last 1 m/s.")
          .number("brake_max_force", &P::brake_max_force, 500.0, 20000.0, "N",
                  "Full service (and EBS) braking force at the ground, all wheels.")
          .number("brake_front_share", &P::brake_front_share, 0.3, 0.9, "", "Brake balance: share on the front axle.")
          .number("air_density", &P::air_density, 0.9, 1.4, "kg/m³", "Density of the air.")
          .number("drag_area", &P::drag_area, 0.0, 4.0, "m²", "Aerodynamic drag coefficient times frontal area, Cd·A.")
          .number("downforce_area", &P::downforce_area, 0.0, 8.0, "m²",
                  "Aerodynamic downforce coefficient times area, Cl·A.")
          .number("aero_front_share", &P::aero_front_share, 0.0, 1.0, "", "Share of the downforce on the front axle.")
          .number("roll_stiffness", &P::roll_stiffness, 5000.0, 500000.0, "N·m/rad",
                  "Total roll stiffness: body roll = m·ay·h / stiffness.")
          .number("pitch_stiffness", &P::pitch_stiffness, 5000.0, 500000.0, "N·m/rad",
                  "Pitch stiffness: body pitch = −m·ax·h / stiffness.")
          .number("load_transfer_time_constant", &P::load_transfer_time_constant, 0.0, 0.5, "s",
                  "Lag of the load transfer and body attitude behind the accelerations.")
          .number("steer_dead_time", &P::steer_dead_time, 0.0, 0.5, "s", "Steering actuator dead time.")
          .number("steer_max_rate", &P::steer_max_rate, 0.1, 10.0, "rad/s",
                  "Steering actuator rate limit (wheel angle).")
          .number("speed_kp", &P::speed_kp, 0.0, 20.0, "1/s", "VCU speed controller: proportional gain.")
          .number("speed_ki", &P::speed_ki, 0.0, 20.0, "1/s²", "VCU speed controller: integral gain.")
          .number("speed_integral_limit", &P::speed_integral_limit, 0.0, 20.0, "m/s²",
                  "VCU speed controller: largest acceleration from the integral term.")
          .number("speed_integral_band", &P::speed_integral_band, 0.0, 10.0, "m/s",
                  "VCU speed controller: the integral acts only while the speed error is smaller than this.")
          .number("stop_hold_speed", &P::stop_hold_speed, 0.0, 2.0, "m/s",
                  "With target speed 0 the VCU holds the car on the brakes below this speed.")
          .number("kinematic_speed", &P::kinematic_speed, 0.1, 10.0, "m/s",
                  "Below this speed the kinematic single-track model alone moves the car.")
          .number("dynamic_speed", &P::dynamic_speed, 0.2, 20.0, "m/s",
                  "Above this speed the dynamic single-track model alone moves the car.");
  return s;
}

std::string validate(const VehicleParams& p) {
  const double fields[] = {p.mass,
                           p.yaw_inertia,
                           p.wheelbase,
                           p.track_width,
                           p.cog_height,
                           p.cog_to_rear_axle,
                           p.wheel_radius,
                           p.body_length,
                           p.body_width,
                           p.rear_overhang,
                           p.mu,
                           p.tyre_front_b,
                           p.tyre_front_c,
                           p.tyre_front_e,
                           p.tyre_rear_b,
                           p.tyre_rear_c,
                           p.tyre_rear_e,
                           p.rolling_resistance,
                           p.motor_max_torque,
                           p.motor_max_power,
                           p.drivetrain_efficiency,
                           p.max_speed,
                           p.brake_max_force,
                           p.brake_front_share,
                           p.air_density,
                           p.drag_area,
                           p.downforce_area,
                           p.aero_front_share,
                           p.roll_stiffness,
                           p.pitch_stiffness,
                           p.load_transfer_time_constant,
                           p.steer_dead_time,
                           p.steer_max_rate,
                           p.steer_max_angle,
                           p.speed_kp,
                           p.speed_ki,
                           p.speed_integral_limit,
                           p.speed_integral_band,
                           p.stop_hold_speed,
                           p.kinematic_speed,
                           p.dynamic_speed};
  for (double f : fields)
    if (!std::isfinite(f)) return "a vehicle parameter is not a finite number";
  if (p.mass <= 0 || p.yaw_inertia <= 0 || p.wheel_radius <= 0 || p.mu <= 0)
    return "mass, yaw_inertia, wheel_radius and mu must be positive";
  if (p.cog_to_rear_axle <= 0 || p.cog_to_rear_axle >= p.wheelbase)
    return "cog_to_rear_axle must lie strictly between the axles (0 < cog_to_rear_axle < wheelbase)";
  if (p.rear_overhang >= p.body_length - p.wheelbase)
    return "body_length must cover the wheelbase plus the rear overhang and some front overhang";
  if (p.kinematic_speed >= p.dynamic_speed) return "kinematic_speed must be below dynamic_speed";
  if (p.max_speed <= 1.0) return "max_speed must exceed the 1 m/s torque fade band";
  return {};
}

}  // namespace fsd::sim
