#pragma once
// Rotations from Euler angles as mounting specs and ISO 8855 give them, and the camera's optical axes: one place
// for what the LiDAR mount, the camera mount, the vehicle's attitude and the GNSS-INS attitude all need.
#include "common/geometry.hpp"

namespace fsd {

// Rotation body → parent from Z-Y-X Euler angles (yaw, then pitch, then roll), as ISO 8855 and mounting specs give
// them; pitch positive nose-down is a positive rotation about y.
inline Eigen::Matrix3d rotation_zyx(double yaw, double pitch, double roll) {
  return (Eigen::AngleAxisd(yaw, Vec3::UnitZ()) * Eigen::AngleAxisd(pitch, Vec3::UnitY()) *
          Eigen::AngleAxisd(roll, Vec3::UnitX()))
      .toRotationMatrix();
}

// A mounting (or any 6-DoF pose) from translation and Z-Y-X Euler angles.
inline Pose3 pose_zyx(const Vec3& translation, double yaw, double pitch, double roll) {
  Pose3 T = Pose3::Identity();
  T.linear() = rotation_zyx(yaw, pitch, roll);
  T.translation() = translation;
  return T;
}

// A camera's optical axes (x right, y down, z forward, as OpenCV projects) in its mount frame (x forward, y left,
// z up): mount ← optical.
inline Eigen::Matrix3d mount_from_optical() {
  Eigen::Matrix3d R;
  R << 0, 0, 1, -1, 0, 0, 0, -1, 0;
  return R;
}

}  // namespace fsd
