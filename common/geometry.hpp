#pragma once
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>
#include <numbers>

namespace fsd {

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;
using Pose3 = Eigen::Isometry3d;  // SE(3): map ← body, or any frame pair named at the use site

// Angle wrapped to (-pi, pi].
inline double wrap_angle(double a) {
  a = std::remainder(a, 2.0 * std::numbers::pi);
  return a <= -std::numbers::pi ? a + 2.0 * std::numbers::pi : a;
}

// The z of the cross product of two plane vectors: > 0 when b lies to the left of a.
inline double cross2(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }
// The angle turning `from` onto `to`, in (-pi, pi], counter-clockwise positive.
inline double signed_angle(const Vec2& from, const Vec2& to) { return std::atan2(cross2(from, to), from.dot(to)); }

inline constexpr double deg2rad(double d) { return d * std::numbers::pi / 180.0; }
inline constexpr double rad2deg(double r) { return r * 180.0 / std::numbers::pi; }

// SE(2) pose: position and heading in a plane. Composition follows the usual a ⊕ b = a * b.
struct Pose2 {
  double x = 0.0, y = 0.0, yaw = 0.0;

  Vec2 position() const { return {x, y}; }
  Eigen::Rotation2Dd rotation() const { return Eigen::Rotation2Dd(yaw); }

  // Maps a point given in this pose's frame into the parent frame.
  Vec2 transform(const Vec2& p) const { return rotation() * p + position(); }
  // Maps a point given in the parent frame into this pose's frame.
  Vec2 inverse_transform(const Vec2& p) const { return rotation().inverse() * (p - position()); }

  Pose2 operator*(const Pose2& o) const {
    const Vec2 t = transform(o.position());
    return {t.x(), t.y(), wrap_angle(yaw + o.yaw)};
  }
  Pose2 inverse() const {
    const Vec2 t = rotation().inverse() * (-position());
    return {t.x(), t.y(), wrap_angle(-yaw)};
  }
  Eigen::Isometry2d isometry() const {
    Eigen::Isometry2d T = Eigen::Isometry2d::Identity();
    T.linear() = rotation().toRotationMatrix();
    T.translation() = position();
    return T;
  }
  Pose3 to_pose3(double z = 0.0) const {
    Pose3 T = Pose3::Identity();
    T.linear() = Eigen::AngleAxisd(yaw, Vec3::UnitZ()).toRotationMatrix();
    T.translation() = Vec3(x, y, z);
    return T;
  }
};

// A share of a rigid correction given about a pivot (turn by `yaw` about `pivot`, then shift by `shift`), as a
// transform to apply on the left (p' = pivot + R(share · yaw)(p − pivot) + share · shift): 0 is the identity, 1 the
// whole correction. For corrections applied a part at a time, or spread over an interval.
inline Pose2 share_of_correction(const Vec2& pivot, double yaw, const Vec2& shift, double share) {
  const Vec2 t = pivot + share * shift - Eigen::Rotation2Dd(share * yaw) * pivot;
  return {t.x(), t.y(), share * yaw};
}

// Heading of a 3D pose projected onto the ground plane.
inline Pose2 to_pose2(const Pose3& T) {
  const Vec3 fwd = T.linear() * Vec3::UnitX();
  return {T.translation().x(), T.translation().y(), std::atan2(fwd.y(), fwd.x())};
}

}  // namespace fsd
