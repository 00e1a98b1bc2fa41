#include "drivers/sim/vehicle_truth.hpp"

#include <cmath>

namespace fsd::sim {

double VehicleTruth::speed() const { return std::hypot(vx, vy); }

double VehicleTruth::sideslip() const { return speed() < 0.5 ? 0.0 : std::atan2(vy, vx); }

Pose3 VehicleTruth::body_pose3() const {
  Pose3 T = Pose3::Identity();
  // Z-Y-X (yaw, pitch, roll) as ISO 8855; pitch positive nose-down is a positive rotation about y.
  T.linear() = (Eigen::AngleAxisd(pose.yaw, Vec3::UnitZ()) * Eigen::AngleAxisd(pitch, Vec3::UnitY()) *
                Eigen::AngleAxisd(roll, Vec3::UnitX()))
                   .toRotationMatrix();
  T.translation() = Vec3(pose.x, pose.y, 0.0);
  return T;
}

}  // namespace fsd::sim
