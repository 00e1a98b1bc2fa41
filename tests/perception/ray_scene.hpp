#pragma once
// Hand-made scenes for the LiDAR stage tests: a ground plane of known tilt and height and objects placed by hand
// (cones, tyres, posts, wall panels, anything floating), swept by the 16 lasers of a VLP-16 (−15°..15° every 2°,
// 0.2° azimuth steps) from a sensor pose, with the simulator's analytic ray intersections (drivers/sim
// cone_geometry). The points come out in the sensor frame with laser, azimuth, distance and firing time, as the
// decoder gives them, in firing order.
#include <cmath>
#include <numbers>
#include <optional>
#include <random>
#include <vector>

#include "common/rotation.hpp"
#include "common/types.hpp"
#include "drivers/sim/world/cone_geometry.hpp"

namespace fsd::test {

struct SceneObject {
  enum class Shape { Frustum, Panel } shape = Shape::Frustum;
  Pose3 pose = Pose3::Identity();   // scene ← object (object z up its axis, origin at the base centre / panel start)
  double r0 = 0, r1 = 0, h = 0;     // frustum radii and height; panel: r0 = length
  double reflectivity = 40;         // a cone's body
  double stripe_reflectivity = 40;  // between stripe_low and stripe_high of the height
  double stripe_low = 0, stripe_high = 0;
};

inline SceneObject small_cone_at(double x, double y, double ground_z = 0.0) {
  SceneObject o;
  o.pose.translation() = Vec3(x, y, ground_z);
  o.r0 = 0.114, o.r1 = 0.025, o.h = 0.325;
  return o;
}
inline SceneObject big_cone_at(double x, double y, double ground_z = 0.0) {
  SceneObject o;
  o.pose.translation() = Vec3(x, y, ground_z);
  o.r0 = 0.1425, o.r1 = 0.03, o.h = 0.505;
  return o;
}
inline SceneObject cylinder_at(double x, double y, double radius, double height, double base_z = 0.0) {
  SceneObject o;
  o.pose.translation() = Vec3(x, y, base_z);
  o.r0 = o.r1 = radius, o.h = height;
  return o;
}
// A tyre standing on its tread, axle horizontal along `yaw`.
inline SceneObject standing_tyre_at(double x, double y, double yaw, double radius = 0.3, double width = 0.2) {
  SceneObject o;
  const Eigen::Matrix3d R =
      (Eigen::AngleAxisd(yaw, Vec3::UnitZ()) * Eigen::AngleAxisd(std::numbers::pi / 2, Vec3::UnitY()))
          .toRotationMatrix();
  o.pose.linear() = R;
  o.pose.translation() = Vec3(x, y, radius) - R.col(2) * (width / 2);
  o.r0 = o.r1 = radius, o.h = width;
  return o;
}
// A vertical panel from (x, y) along `yaw`.
inline SceneObject wall_at(double x, double y, double yaw, double length, double height) {
  SceneObject o;
  o.shape = SceneObject::Shape::Panel;
  o.pose.linear() = Eigen::AngleAxisd(yaw, Vec3::UnitZ()).toRotationMatrix();
  o.pose.translation() = Vec3(x, y, 0.0);
  o.r0 = length, o.h = height;
  return o;
}

struct RayScene {
  // Ground z = a·x + b·y + h in the scene frame.
  double a = 0, b = 0, h = 0;
  double ground_reflectivity = 12;
  std::vector<SceneObject> objects;
  double range_noise = 0.0;  // σ of the range, m
  std::uint32_t seed = 1;

  // One revolution of a VLP-16 at `scene_from_sensor`, points in the sensor frame. `time_of` gives each firing's
  // time from its azimuth index (0..1799); `pose_at` the sensor pose at that time (a moving sensor), else fixed.
  Scan sweep(const Pose3& scene_from_sensor, double max_range = 100.0) const {
    return sweep_moving([&](double) { return scene_from_sensor; }, max_range);
  }
  template <class PoseAt>
  Scan sweep_moving(PoseAt&& pose_at, double max_range = 100.0, double period = 0.1) const {
    Scan scan;
    std::mt19937 rng(seed);
    std::normal_distribution<double> noise(0.0, range_noise);
    constexpr int kSteps = 1800;
    for (int s = 0; s < kSteps; ++s) {
      const double t = period * s / kSteps;
      const Pose3 T = pose_at(t);
      const double az = deg2rad(0.2 * s);  // clockwise from +x
      for (int laser = 0; laser < 16; ++laser) {
        const double elev = deg2rad(-15.0 + 2.0 * laser);
        const Vec3 dir_s(std::cos(elev) * std::cos(az), -std::cos(elev) * std::sin(az), std::sin(elev));
        const Vec3 o = T.translation(), d = T.linear() * dir_s;
        auto hit = cast(o, d, max_range);
        if (!hit) continue;
        double dist = hit->first + (range_noise > 0 ? noise(rng) : 0.0);
        if (dist < 0.5) continue;
        Point p;
        const Vec3 ps = dist * dir_s;
        p.x = static_cast<float>(ps.x()), p.y = static_cast<float>(ps.y()), p.z = static_cast<float>(ps.z());
        p.intensity = static_cast<float>(hit->second);
        p.ring = static_cast<std::uint16_t>(laser);
        p.azimuth = static_cast<float>(az);
        p.distance = static_cast<float>(dist);
        p.t = t;
        scan.points.push_back(p);
      }
    }
    scan.stamp = scan.points.empty() ? 0.0 : scan.points.front().t;
    return scan;
  }

  // Nearest hit (distance, reflectivity) of the ray o + t·d.
  std::optional<std::pair<double, double>> cast(const Vec3& o, const Vec3& d, double max_range) const {
    std::optional<std::pair<double, double>> best;
    // Ground: n·(p) = h with n = (−a, −b, 1).
    const double denom = d.z() - a * d.x() - b * d.y();
    if (std::abs(denom) > 1e-12) {
      const double t = (h - (o.z() - a * o.x() - b * o.y())) / denom;
      if (t > 0 && t < max_range) best = {t, ground_reflectivity};
    }
    for (const auto& ob : objects) {
      const Pose3 inv = ob.pose.inverse();
      const Vec3 lo = inv * o, ld = inv.linear() * d;
      const double t_max = best ? best->first : max_range;
      const auto hit = ob.shape == SceneObject::Shape::Panel
                           ? sim::intersect_panel(lo, ld, ob.r0, ob.h, 0.0, t_max)
                           : sim::intersect_frustum(lo, ld, ob.r0, ob.r1, ob.h, 0.0, t_max);
      if (!hit) continue;
      const double f = ob.h > 0 ? hit->point.z() / ob.h : 0.0;
      const bool stripe = f >= ob.stripe_low && f <= ob.stripe_high && ob.stripe_high > ob.stripe_low;
      best = {hit->t, stripe ? ob.stripe_reflectivity : ob.reflectivity};
    }
    return best;
  }
};

}  // namespace fsd::test
