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
  l.kappa_rate_max = kappa_rate_max;
  l.traction_ellipse = traction_ellipse;
  return l;
}

SpeedLimits SpeedConfig::known() const {
  SpeedLimits l = realtime();
  l.mu = mu * mu_margin_known;
  l.v_max = v_max;
  return l;
}

std::optional<Path> straight_from_cones(const std::vector<Cone>& cones, const Pose2& start, double length, double ds) {
  // The lane from the start heading first, then from its own fit: the start pose may be a few degrees off the
  // lane, which a long lane turns into metres.
  Vec2 origin = start.position(), dir(std::cos(start.yaw), std::sin(start.yaw));
  double reach = 8.0;
  Vec2 centre = origin;
  bool fitted = false;
  for (int round = 0; round < 3; ++round) {
    const Vec2 left_axis(-dir.y(), dir.x());
    std::vector<Vec2> pts;
    for (const auto& c : cones) {
      if (!c.position.allFinite()) continue;
      const Vec2 m = c.position.head<2>();
      if ((m - origin).dot(dir) < -5.0 || std::abs((m - origin).dot(left_axis)) > reach) continue;
      pts.push_back(m);
    }
    if (pts.size() < 8) break;
    // Direction: principal axis of the cone cloud (a long narrow lane).
    Vec2 mean = Vec2::Zero();
    for (const auto& p : pts) mean += p;
    mean /= static_cast<double>(pts.size());
    Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
    for (const auto& p : pts) cov += (p - mean) * (p - mean).transpose();
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(cov);
    Vec2 d = eig.eigenvectors().col(1);
    if (d.dot(dir) < 0) d = -d;
    const Vec2 left(-d.y(), d.x());
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
    if (nl < 4 || nr < 4) break;
    centre = mean + 0.5 * (sum_l / nl + sum_r / nr) * left;
    dir = d;
    origin = centre;
    reach = 5.0;
    fitted = true;
  }
  if (!fitted) return std::nullopt;
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
