#include "common/car.hpp"

#include <string>

#include "common/rotation.hpp"

namespace fsd {

Pose3 SensorMount::body_from_sensor() const { return pose_zyx(Vec3(x, y, z), yaw, pitch, roll); }

namespace {
const ConfigSection<CarDescription>& body_section() {
  using C = CarDescription;
  static const auto s =
      ConfigSection<C>("car")
          .number("wheelbase", &C::wheelbase, 1.0, 4.0, "m", "Rear axle to front axle (rules: at least 1.525 m).")
          .number("max_steer", &C::max_steer, 0.1, 1.0, "rad", "Front wheel angle at the steering lock.")
          .number("mass", &C::mass, 50.0, 2000.0, "kg", "Mass of the car with the driverless kit.")
          .number("body_length", &C::body_length, 1.0, 6.0, "m", "Body outline, tail to nose.")
          .number("rear_overhang", &C::rear_overhang, 0.0, 2.0, "m", "Body outline behind the rear axle.")
          .number("body_width", &C::body_width, 0.5, 3.0, "m", "Body outline width over the tyres.");
  return s;
}

const ConfigSection<SensorMount>& lidar_mount_section() {
  using M = SensorMount;
  static const auto s =
      ConfigSection<M>("car.lidar", CarDescription{}.lidar)
          .number("x", &M::x, -5.0, 5.0, "m", "LiDAR origin ahead of the rear-axle centre.")
          .number("y", &M::y, -2.0, 2.0, "m", "LiDAR origin left of the rear-axle centre.")
          .number("z", &M::z, 0.05, 3.0, "m", "LiDAR origin above the ground.")
          .number("roll", &M::roll, -0.5, 0.5, "rad", "LiDAR mount roll (Z-Y-X).")
          .number("pitch", &M::pitch, -0.5, 0.5, "rad", "LiDAR mount pitch, positive tilts its front down (Z-Y-X).")
          .number("yaw", &M::yaw, -3.15, 3.15, "rad", "LiDAR mount yaw (Z-Y-X).");
  return s;
}

const ConfigSection<Lever>& antenna_section() {
  static const auto s = ConfigSection<Lever>("car.gnss_antenna", CarDescription{}.gnss_antenna)
                            .number("x", &Lever::x, -10.0, 10.0, "m", "GNSS antenna ahead of the rear-axle centre.")
                            .number("y", &Lever::y, -10.0, 10.0, "m", "GNSS antenna left of the rear-axle centre.")
                            .number("z", &Lever::z, -10.0, 10.0, "m", "GNSS antenna above the ground.");
  return s;
}
}  // namespace

void describe_car(ConfigSchema& schema) {
  if (schema.find("car.wheelbase")) return;  // every library that reads the car declares it; once is enough
  body_section().describe(schema);
  lidar_mount_section().describe(schema);
  antenna_section().describe(schema);
}

CarDescription read_car(const Config& config) {
  CarDescription c = body_section().read(config);
  c.lidar = lidar_mount_section().read(config);
  c.gnss_antenna = antenna_section().read(config);
  if (c.nose() <= c.wheelbase)
    throw ConfigError(config.source() + ": car.body_length - car.rear_overhang (" + std::to_string(c.nose()) +
                      " m) puts the nose behind the front axle (car.wheelbase " + std::to_string(c.wheelbase) + " m)");
  return c;
}

}  // namespace fsd
