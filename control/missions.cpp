#include "control/missions.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

namespace fsd {

SpeedLimits SpeedConfig::realtime() const {
  SpeedLimits l;
  l.mu = mu * mu_margin_realtime;
  l.a_accel_max = a_accel_max;
  l.a_brake_max = a_brake_max;
  l.power_max = power_max;
  l.mass = mass;
  l.v_max = std::min(v_max, v_max_realtime);
  return l;
}

SpeedLimits SpeedConfig::known() const {
  SpeedLimits l = realtime();
  l.mu = mu * mu_margin_known;
  l.v_max = v_max;
  return l;
}

std::optional<Path> straight_from_cones(const std::vector<Cone>& cones, const Pose2& start, double length,
                                        double ds) {
  std::vector<Vec2> pts;
  for (const auto& c : cones) {
    if (!c.position.allFinite()) continue;
    const Vec2 m = c.position.head<2>();
    const Vec2 l = start.inverse_transform(m);
    if (l.x() < -5.0 || std::abs(l.y()) > 8.0) continue;
    pts.push_back(m);
  }
  if (pts.size() < 8) return std::nullopt;
  // Direction: principal axis of the cone cloud (a long narrow lane).
  Vec2 mean = Vec2::Zero();
  for (const auto& p : pts) mean += p;
  mean /= static_cast<double>(pts.size());
  Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
  for (const auto& p : pts) cov += (p - mean) * (p - mean).transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(cov);
  Vec2 dir = eig.eigenvectors().col(1);
  if (dir.dot(Vec2(std::cos(start.yaw), std::sin(start.yaw))) < 0) dir = -dir;
  const Vec2 left(-dir.y(), dir.x());
  // Lateral centre: midway between the mean offsets of the cones on either side of the axis.
  double sum_l = 0, sum_r = 0;
  int nl = 0, nr = 0;
  for (const auto& p : pts) {
    const double lat = (p - mean).dot(left);
    if (lat > 0) {
      sum_l += lat;
      ++nl;
    } else {
      sum_r += lat;
      ++nr;
    }
  }
  if (nl < 4 || nr < 4) return std::nullopt;
  const Vec2 centre = mean + 0.5 * (sum_l / nl + sum_r / nr) * left;
  const double s0 = (start.position() - centre).dot(dir);
  Path p;
  for (double s = 0; s <= length + 1e-9; s += ds) p.points.push_back({centre + (s0 + s) * dir, 0, 0, 0, 0});
  compute_geometry(p);
  return p;
}

double stop_speed(double v_finish, double travelled, double decel, double max_distance) {
  const double v0 = std::max(0.0, v_finish);
  // Aim at 80 % of the allowed distance: the speed loop lags the target.
  const double a = std::max({decel, v0 * v0 / (1.6 * std::max(max_distance, 1.0)), 0.1});
  const double d_stop = v0 * v0 / (2.0 * a);
  const double left = d_stop - std::max(0.0, travelled);
  return left > 0 ? std::sqrt(2.0 * a * left) : 0.0;
}

}  // namespace fsd
