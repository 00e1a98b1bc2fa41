#pragma once
// The ground plane z = a·x + b·y + h in the detector's frame (DESIGN.md §5: the paper's y = kx + jz + h with y up).
#include <cmath>
#include <cstddef>

#include "common/geometry.hpp"

namespace fsd {

struct GroundPlane {
  double a = 0.0, b = 0.0, h = 0.0;
  bool valid = false;       // found by the fit (else a fallback: the previous plane or the configured nominal one)
  std::size_t inliers = 0;  // points within the inlier threshold
  double rms = 0.0;         // RMS distance of the inliers from the plane, m

  double z_at(double x, double y) const { return a * x + b * y + h; }
  // Signed distance of a point from the plane, positive above (the paper's eq. 3 with the point-to-plane norm
  // sqrt(1 + a² + b²); the paper's denominator also has h², a typo).
  double height_of(double x, double y, double z) const { return (z - z_at(x, y)) * inv_norm(); }
  double inv_norm() const { return 1.0 / std::sqrt(1.0 + a * a + b * b); }
  Vec3 normal() const { return Vec3(-a, -b, 1.0).normalized(); }
  double tilt() const { return std::atan(std::hypot(a, b)); }  // angle between the plane and z = 0, rad
  // The rotation that levels the frame on this plane (its normal to +z, no turn about z): the body's roll and
  // pitch on its springs, which planar odometry poses do not carry.
  Pose3 level_from_frame() const {
    Pose3 T = Pose3::Identity();
    T.linear() = Eigen::Quaterniond::FromTwoVectors(normal(), Vec3::UnitZ()).toRotationMatrix();
    return T;
  }
};

}  // namespace fsd
