#pragma once
// Body forces of the virtual car that do not come from the tyres' slip: aerodynamics, rolling resistance,
// axle normal loads and the powertrain's drive force limit. Shared by the vehicle model and the VCU's speed
// controller (which feeds drag and rolling resistance forward).
#include "drivers/sim/vehicle/vehicle_params.hpp"

namespace fsd::sim {

double drag_force(const VehicleParams& p, double speed);  // N, opposing motion
double downforce(const VehicleParams& p, double speed);   // N, total on both axles
double rolling_resistance_force(const VehicleParams& p);  // N, magnitude while rolling

struct AxleLoads {
  double front = 0, rear = 0;  // N, never negative
};
// Static weight split by the CoG position, plus longitudinal load transfer m·ax·h/L (ax > 0 loads the rear)
// and the downforce split by its centre of pressure.
AxleLoads axle_loads(const VehicleParams& p, double speed, double ax);

// Largest drive force at the rear wheels' contact patches (N) at `speed`: the motor torque limit, the power
// limit after the drivetrain, and a fade to zero over the last 1 m/s before max_speed (the motor speed limit).
double drive_force_limit(const VehicleParams& p, double speed);

inline constexpr double kMaxSpeedFadeBand = 1.0;  // m/s

}  // namespace fsd::sim
