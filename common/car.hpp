#pragma once
// The car, described once: its size, steering, mass and where its sensors sit. Control, the drivers, perception,
// the dashboard and the virtual car all read these keys ("car.*"); the virtual car departs from them only by its own
// "sim.mismatch.*" keys (a model mismatch on purpose). The camera is described by its calibration file
// (drivers.camera.calibration: intrinsics and mount are calibrated together); the virtual car's camera by sim.camera.
#include <cmath>

#include "common/config.hpp"
#include "common/geometry.hpp"

namespace fsd {

// A sensor on the vehicle body frame (rear-axle centre on the ground, x forward, y left, z up), Z-Y-X angles.
struct SensorMount {
  double x = 0, y = 0, z = 0;           // m
  double roll = 0, pitch = 0, yaw = 0;  // rad; pitch positive tilts the sensor's front down
  Pose3 body_from_sensor() const;
};

struct Lever {
  double x = 0, y = 0, z = 0;  // m, on the vehicle body frame
  Vec3 vector() const { return Vec3(x, y, z); }
};

struct CarDescription {
  double wheelbase = 1.53;     // m, rear to front axle (rules: ≥ 1.525 m)
  double max_steer = 0.5;      // rad, front wheel angle at the lock
  double mass = 230.0;         // kg, with the driverless kit
  double body_length = 2.9;    // m, tail to nose
  double rear_overhang = 0.5;  // m, body behind the rear axle
  double body_width = 1.4;     // m, over the tyres
  SensorMount lidar{2.0, 0.0, 0.35};
  Lever gnss_antenna{0.5, 0.0, 1.2};  // the antenna's phase centre

  double nose() const { return body_length - rear_overhang; }  // m ahead of the rear axle
};

// The kinematic bicycle: the path curvature a front wheel angle gives, tan(δ) / L (0 without a wheelbase), and the
// wheel angle a curvature needs, atan(L·κ).
inline double kinematic_curvature(double steer, double wheelbase) {
  return wheelbase > 0 ? std::tan(steer) / wheelbase : 0.0;
}
inline double kinematic_steer(double curvature, double wheelbase) { return std::atan(wheelbase * curvature); }

// Adds the car's keys unless the schema has them already (each library that reads the car calls it).
void describe_car(ConfigSchema& schema);
// Throws ConfigError when the values cannot be one car (a nose behind the front axle).
CarDescription read_car(const Config& config);

}  // namespace fsd
