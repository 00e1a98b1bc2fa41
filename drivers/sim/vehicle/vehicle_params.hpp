#pragma once
// Parameters of the virtual car: a Formula Student electric car with rear-wheel drive, wings and a driverless kit.
// Defaults are plausible values for such a car. The fields the car's own description has (mass, wheelbase, body,
// steering lock) come from "car.*" plus "sim.mismatch.*" (drivers/sim/vehicle/model_mismatch.hpp); every other field is a
// configuration key under "sim.vehicle".
#include <string>

#include "common/config.hpp"

namespace fsd::sim {

inline constexpr double kGravity = 9.81;  // m/s²

struct VehicleParams {
  // Chassis
  double mass = 230.0;             // kg, car with driverless equipment, no driver
  double yaw_inertia = 110.0;      // kg·m² about the vertical axis through the CoG
  double wheelbase = 1.53;         // m
  double track_width = 1.2;        // m, same front and rear
  double cog_height = 0.30;        // m above the ground
  double cog_to_rear_axle = 0.72;  // m; 47 % of the static weight on the front axle
  double wheel_radius = 0.23;      // m, loaded rolling radius
  // Body outline on the ground (for cone contacts)
  double body_length = 2.9;    // m, nose to diffuser
  double body_width = 1.4;     // m, over the tyres
  double rear_overhang = 0.5;  // m, body behind the rear axle
  // Tyres: Pacejka magic formula Fy = D sin(C atan(Bα − E(Bα − atan Bα))) with D = μ·Fz per axle
  double mu = 1.4;
  double tyre_front_b = 11.0;
  double tyre_front_c = 1.5;
  double tyre_front_e = 0.0;
  double tyre_rear_b = 12.0;
  double tyre_rear_c = 1.5;
  double tyre_rear_e = 0.0;
  double rolling_resistance = 0.015;  // coefficient on the static weight
  // Powertrain (rear-wheel drive)
  double motor_max_torque = 700.0;   // N·m, both rear wheels together
  double motor_max_power = 80000.0;  // W, accumulator power limit of the rules
  double drivetrain_efficiency = 0.9;
  double max_speed = 32.0;  // m/s, motor speed limit; torque fades to zero over the last 1 m/s
  // Brakes
  double brake_max_force =
      4500.0;  // N at the ground, all wheels, full service braking (enough to reach the tyre limit)
  double brake_front_share = 0.7;
  // Aerodynamics
  double air_density = 1.225;      // kg/m³
  double drag_area = 1.3;          // Cd·A, m²
  double downforce_area = 3.0;     // Cl·A, m²
  double aero_front_share = 0.45;  // share of the downforce on the front axle
  // Body attitude from load transfer
  double roll_stiffness = 55000.0;            // N·m/rad (~0.7° per g)
  double pitch_stiffness = 80000.0;           // N·m/rad (~0.5° per g)
  double load_transfer_time_constant = 0.08;  // s, suspension lag of load transfer and attitude
  // Steering actuator (front wheel angle)
  double steer_dead_time = 0.05;  // s
  double steer_max_rate = 1.2;    // rad/s
  double steer_max_angle = 0.5;   // rad (≈ 29°: the rules' 9 m hairpin on a 3 m track needs ≥ 0.47)
  // VCU speed controller: acceleration = kp·e + ki·∫e plus drag and rolling-resistance feed-forward
  double speed_kp = 2.0;              // 1/s
  double speed_ki = 0.2;              // 1/s²
  double speed_integral_limit = 1.0;  // m/s², largest acceleration the integral term may ask for
  double speed_integral_band = 0.5;   // m/s, the integral acts only while the error is smaller
  double stop_hold_speed = 0.3;       // m/s: with target 0 below this speed the VCU holds the car on the brakes
  // Blend of the kinematic and the dynamic single-track model
  double kinematic_speed = 1.5;  // m/s, pure kinematic below
  double dynamic_speed = 3.0;    // m/s, pure dynamic above

  double cog_to_front_axle() const { return wheelbase - cog_to_rear_axle; }
};

// Every field under the prefix "sim.vehicle", with bounds, unit and doc.
const ConfigSection<VehicleParams>& vehicle_section();

// Empty when the parameters describe a consistent car, else what is wrong (checks across fields that the
// per-key bounds cannot express).
std::string validate(const VehicleParams& p);

}  // namespace fsd::sim
