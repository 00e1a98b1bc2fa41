// The three steering laws of PathFollower. Each takes the latency-predicted rear-axle pose.
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "common/car.hpp"
#include "control/tracking/follower.hpp"

namespace fsd {

namespace {

// Point at arc length s; past the end of an open path, continued straight along its last heading so a
// look-ahead never shrinks onto the end point.
Vec2 point_ahead(const Path& path, double s) {
  const double len = path.length();
  if (path.closed || s <= len) return sample(path, s).p;
  const PathPoint& e = path.points.back();
  return e.p + (s - len) * Vec2(std::cos(e.yaw), std::sin(e.yaw));
}

}  // namespace

double PathFollower::pure_pursuit(const Path& path, const Pose2& pose, double v, double s, Vec2& target) const {
  const double lookahead = std::clamp(config_.pp_gain * v + config_.pp_min, config_.pp_min, config_.pp_max);
  target = point_ahead(path, s + lookahead);
  const Vec2 local = pose.inverse_transform(target);
  const double ld2 = local.squaredNorm();
  if (ld2 < 1e-6) return 0.0;
  // Arc through the rear axle tangent to the heading and through the target: κ = 2·y / ld².
  return std::atan(config_.wheelbase * 2.0 * local.y() / ld2);
}

double PathFollower::stanley(const Path& path, const Pose2& pose, double v, double s) const {
  const double L = config_.wheelbase;
  const Vec2 front = pose.position() + L * Vec2(std::cos(pose.yaw), std::sin(pose.yaw));
  const auto pf = project(path, front, s + L, config_.search_window, config_.search_window);
  if (!pf) return 0.0;
  // The heading error at the front axle already holds the steady-state steer of a curve (the front wheels
  // point along the path where they are), so no separate curvature feed-forward is added.
  const double heading_error = wrap_angle(pf->yaw - pose.yaw);
  const double correction = -std::atan(config_.stanley_gain * pf->lateral / (config_.stanley_softening + v));
  return heading_error + correction;
}

double PathFollower::lqr(const Path& path, const PathProjection& proj, const Pose2& pose, double v) const {
  // Error dynamics of the kinematic bicycle about the path (e lateral, θ heading error, u = δ − δ_ff):
  //   ė = v·θ,  θ̇ = (v/L)·u;  discretised exactly (zero-order hold) over dt.
  const double L = config_.wheelbase, dt = config_.lqr_dt;
  const double vv = std::max(v, 1.0);  // gains stay finite and meaningful when rolling off the line
  Eigen::Matrix2d A;
  A << 1, vv * dt, 0, 1;
  Eigen::Vector2d B(vv * vv * dt * dt / (2 * L), vv * dt / L);
  Eigen::Matrix2d Q = Eigen::Matrix2d::Zero();
  Q(0, 0) = config_.lqr_q_lateral;
  Q(1, 1) = config_.lqr_q_heading;
  const double R = config_.lqr_r;
  // Discrete Riccati recursion to its fixed point (2×2, converges in tens of steps).
  Eigen::Matrix2d P = Q;
  for (int i = 0; i < 500; ++i) {
    const double s = R + B.dot(P * B);
    const Eigen::RowVector2d K = (B.transpose() * P * A) / s;
    const Eigen::Matrix2d Pn = A.transpose() * P * A - A.transpose() * P * B * K + Q;
    const bool done = (Pn - P).cwiseAbs().maxCoeff() < 1e-9;
    P = Pn;
    if (done) break;
  }
  const Eigen::RowVector2d K = (B.transpose() * P * A) / (R + B.dot(P * B));
  // Feed-forward from the curvature a little ahead: the steering actuator needs time to wind on.
  const double kappa_ff = sample(path, proj.s + v * std::max(0.0, config_.lqr_preview)).kappa;
  // Cornering, the rear tyres run at a slip angle: the rear axle moves along the path while the car points
  // into the corner by that angle. Regulating the heading error to zero would push the car wide; its steady
  // value (slip per lateral acceleration × v²κ) is taken off first (Kapania & Gerdes' sideslip feed-forward).
  const double heading_ss = expected_sideslip(v, proj.kappa);
  const Eigen::Vector2d x(proj.lateral, wrap_angle(pose.yaw - proj.yaw - heading_ss));
  return kinematic_steer(kappa_ff, L) + config_.understeer * v * v * kappa_ff - K.dot(x);
}

}  // namespace fsd
