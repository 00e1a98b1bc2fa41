#include "control/planning/footprint.hpp"

namespace fsd {

std::vector<Obstacle> obstacles_of(const std::vector<Cone>& cones, double cone_radius, double big_cone_radius) {
  std::vector<Obstacle> out;
  out.reserve(cones.size());
  for (const auto& c : cones)
    if (c.position.allFinite())
      out.push_back({c.position.head<2>(), c.colour == ConeColour::BigOrange ? big_cone_radius : cone_radius});
  return out;
}

namespace {
// The least clearance of the body at `pose` to the obstacles near it, and which one.
std::pair<double, int> nearest(const Pose2& pose, const std::vector<Obstacle>& obstacles, const Body& body,
                               double within) {
  double best = std::numeric_limits<double>::infinity();
  int which = -1;
  const Vec2 at = pose.position();
  const double reach = body.reach();
  for (std::size_t k = 0; k < obstacles.size(); ++k) {
    const Obstacle& o = obstacles[k];
    const double r = reach + o.radius + within;
    if ((o.p - at).squaredNorm() > r * r) continue;  // too far for the body to come within `within`
    const double d = body_clearance(pose, o, body);
    if (d < best) best = d, which = static_cast<int>(k);
  }
  return {best, which};
}
}  // namespace

SweepResult sweep_body(const Path& path, const std::vector<Obstacle>& obstacles, const Body& body, double margin,
                       double step, double s_from, double s_to) {
  SweepResult r;
  if (path.empty() || step <= 0) return r;
  const double length = path.length();
  if (!path.closed) {
    s_from = std::clamp(s_from, 0.0, length);
    s_to = std::clamp(s_to, 0.0, length);
  } else if (!std::isfinite(s_to)) {
    s_to = s_from + length;
  }
  // Obstacles farther than this from the body are not measured (their clearance is only needed when short).
  constexpr double kWithin = 1.0;
  for (double s = s_from;; s += step) {
    const double at = std::min(s, s_to);
    const PathPoint q = sample(path, at);
    const auto [d, which] = nearest({q.p.x(), q.p.y(), q.yaw}, obstacles, body, std::max(kWithin, margin));
    if (d < r.min_clearance) r.min_clearance = d, r.min_s = at;
    if (d < margin && !std::isfinite(r.first_short_s)) {
      r.first_short_s = at;
      r.first_short_obstacle = which;
    }
    if (at >= s_to) break;
  }
  return r;
}

PoseSweepResult sweep_poses(const std::vector<Pose2>& poses, const std::vector<Obstacle>& obstacles, const Body& body,
                            double margin) {
  PoseSweepResult r;
  for (std::size_t i = 0; i < poses.size(); ++i) {
    const auto [d, which] = nearest(poses[i], obstacles, body, std::max(1.0, margin));
    if (d < margin) {
      r.first_short = static_cast<int>(i);
      r.obstacle = which;
      r.clearance = d;
      return r;
    }
    r.clearance = std::min(r.clearance, d);
  }
  return r;
}

}  // namespace fsd
