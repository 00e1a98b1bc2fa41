#include "drivers/sim/vehicle/vehicle_truth.hpp"

#include <cmath>

#include "common/rotation.hpp"

namespace fsd::sim {

double VehicleTruth::speed() const { return std::hypot(vx, vy); }

double VehicleTruth::sideslip() const { return speed() < 0.5 ? 0.0 : std::atan2(vy, vx); }

Pose3 VehicleTruth::body_pose3() const { return pose_zyx(Vec3(pose.x, pose.y, 0.0), pose.yaw, pitch, roll); }

}  // namespace fsd::sim
