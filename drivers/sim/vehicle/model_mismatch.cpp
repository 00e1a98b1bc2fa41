#include "drivers/sim/vehicle/model_mismatch.hpp"

#include "drivers/sim/sensors/gnss_model.hpp"
#include "drivers/sim/sensors/lidar_model.hpp"
#include "drivers/sim/vehicle/vehicle_params.hpp"

namespace fsd::sim {

const ConfigSection<ModelMismatch>& model_mismatch_section() {
  using M = ModelMismatch;
  static const auto s =
      ConfigSection<M>("sim.mismatch")
          .number("wheelbase", &M::wheelbase, -0.3, 0.3, "m", "The simulated car's wheelbase minus car.wheelbase.")
          .number("mass", &M::mass, -100.0, 200.0, "kg", "The simulated car's mass minus car.mass.")
          .number("max_steer", &M::max_steer, -0.2, 0.1, "rad", "The simulated steering lock minus car.max_steer.")
          .number("lidar_x", &M::lidar_x, -0.5, 0.5, "m", "The simulated LiDAR sits this much ahead of car.lidar.x.")
          .number("lidar_y", &M::lidar_y, -0.5, 0.5, "m", "... this much left of car.lidar.y.")
          .number("lidar_z", &M::lidar_z, -0.3, 0.5, "m", "... this much above car.lidar.z.")
          .number("lidar_roll", &M::lidar_roll, -0.1, 0.1, "rad", "... rolled by this beyond car.lidar.roll.")
          .number("lidar_pitch", &M::lidar_pitch, -0.1, 0.1, "rad", "... pitched by this beyond car.lidar.pitch.")
          .number("lidar_yaw", &M::lidar_yaw, -0.1, 0.1, "rad", "... yawed by this beyond car.lidar.yaw.")
          .number("antenna_x", &M::antenna_x, -1.0, 1.0, "m",
                  "The simulated antenna sits this much ahead of car.gnss_antenna.x.")
          .number("antenna_y", &M::antenna_y, -1.0, 1.0, "m", "... this much left of car.gnss_antenna.y.")
          .number("antenna_z", &M::antenna_z, -1.0, 1.0, "m", "... this much above car.gnss_antenna.z.")
          .number("camera_roll", &M::camera_roll, -0.1, 0.1, "rad",
                  "The simulated camera is rolled by this beyond the mount its calibration (sim.camera) gives.")
          .number("camera_pitch", &M::camera_pitch, -0.1, 0.1, "rad", "... pitched by this (down positive).")
          .number("camera_yaw", &M::camera_yaw, -0.1, 0.1, "rad", "... yawed by this.");
  return s;
}

void apply_car(const CarDescription& car, const ModelMismatch& m, VehicleParams& vehicle, LidarConfig& lidar,
               GnssModelConfig& gnss) {
  vehicle.wheelbase = car.wheelbase + m.wheelbase;
  vehicle.mass = car.mass + m.mass;
  vehicle.steer_max_angle = car.max_steer + m.max_steer;
  vehicle.body_length = car.body_length;
  vehicle.body_width = car.body_width;
  vehicle.rear_overhang = car.rear_overhang;
  lidar.x = car.lidar.x + m.lidar_x;
  lidar.y = car.lidar.y + m.lidar_y;
  lidar.z = car.lidar.z + m.lidar_z;
  lidar.roll = car.lidar.roll + m.lidar_roll;
  lidar.pitch = car.lidar.pitch + m.lidar_pitch;
  lidar.yaw = car.lidar.yaw + m.lidar_yaw;
  gnss.antenna_x = car.gnss_antenna.x + m.antenna_x;
  gnss.antenna_y = car.gnss_antenna.y + m.antenna_y;
  gnss.antenna_z = car.gnss_antenna.z + m.antenna_z;
}

}  // namespace fsd::sim
