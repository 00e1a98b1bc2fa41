#pragma once
// The virtual car is built from the car's description (common/car.hpp), the same keys control and the drivers
// read, so by default the software knows the car exactly. "sim.mismatch.*" makes the simulated car differ from
// that description on purpose: a wheelbase measured wrong, a heavier car, a LiDAR or antenna bolted elsewhere, a
// camera knocked askew after its calibration.
#include "common/car.hpp"
#include "common/config.hpp"

namespace fsd::sim {

struct LidarConfig;
struct GnssModelConfig;
struct VehicleParams;

struct ModelMismatch {
  double wheelbase = 0, mass = 0, max_steer = 0;             // added to the car's
  double lidar_x = 0, lidar_y = 0, lidar_z = 0;              // m, added to car.lidar
  double lidar_roll = 0, lidar_pitch = 0, lidar_yaw = 0;     // rad
  double antenna_x = 0, antenna_y = 0, antenna_z = 0;        // m, added to car.gnss_antenna
  double camera_roll = 0, camera_pitch = 0, camera_yaw = 0;  // rad: the camera turned from its calibrated mount
};
const ConfigSection<ModelMismatch>& model_mismatch_section();  // "sim.mismatch"

// The simulated car's body, steering, mass, LiDAR mount and antenna: the description plus the mismatch. (The
// camera's turn applies to the rendering alone: the daemon keeps the calibration of sim.camera.)
void apply_car(const CarDescription& car, const ModelMismatch& m, VehicleParams& vehicle, LidarConfig& lidar,
               GnssModelConfig& gnss);

}  // namespace fsd::sim
