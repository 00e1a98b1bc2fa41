#include "localization/fusion/complementary_filter.hpp"

#include <algorithm>
#include <cmath>

namespace fsd::fusion {

namespace {
constexpr double kTrackSpan = 30.0;  // s of accepted fixes kept for course and scale
}  // namespace

ComplementaryFilter::ComplementaryFilter(const FusionConfig& cfg)
    : cfg_(cfg), gate_(cfg.gnss), heading_init_(cfg.common.heading_baseline_m) {}

void ComplementaryFilter::advance(Stamp t) {
  const double dt = t - t_;
  if (dt <= 0) return;
  t_ = t;
  const double ym = pose_.yaw + 0.5 * r_ * dt;
  const Vec2 step = Eigen::Rotation2Dd(ym) * Vec2(vx_, vy_) * dt;
  pose_.x += step.x();
  pose_.y += step.y();
  pose_.yaw = wrap_angle(pose_.yaw + r_ * dt);
  dr_path_ += step;
  motion_since_fix_ += step;
  drift_since_fix_ += step.norm();
  yaw_var_ += std::pow(cfg_.ekf.initial_bias_sigma, 2) * dt * 0.01;
}

void ComplementaryFilter::on_imu(const ImuSample& s) {
  if (!std::isfinite(s.gyro.z())) return;
  const double dt_prev = std::max(0.0, s.t - last_motion_);
  last_motion_ = s.t;
  if (speed_ < cfg_.common.standstill_speed && dt_prev < 1.0) {
    const double a = dt_prev / (cfg_.complementary.standstill_bias_time_constant_s + dt_prev);
    bias_ += a * (s.gyro.z() - bias_);
  }
  // A standing car does not turn: what the gyro reads there is bias, not heading change.
  if (s.t > odometry_until_) r_ = speed_ < cfg_.common.standstill_speed ? 0.0 : s.gyro.z() - bias_;
}

void ComplementaryFilter::on_speed(const BodySpeed& s) {
  if (!std::isfinite(s.vx) || (s.has_vy && !std::isfinite(s.vy))) return;
  // One speed source drives the motion: the optical sensor where present, the wheels (slip and all) without it.
  if (s.source == BodySpeed::Source::Optical)
    last_optical_ = s.t;
  else if (s.t - last_optical_ < 0.2)
    return;
  last_motion_ = s.t;
  speed_ = s.has_vy ? std::hypot(s.vx, s.vy) : std::abs(s.vx);
  if (s.t <= odometry_until_) return;  // LiDAR odometry drives the motion
  // v_ref = v_sensor − r × lever; the optical reading divided by its scale first.
  const double k = s.source == BodySpeed::Source::Optical ? scale_ : 1.0;
  vx_ = s.vx / k + r_ * s.lever.y();
  vy_ = s.has_vy ? s.vy / k - r_ * s.lever.x() : 0.0;
}

void ComplementaryFilter::on_odometry(const OdometryIncrement& o) {
  const double dt = o.t1 - o.t0;
  if (!(dt > 1e-3) || !std::isfinite(o.delta.x) || !std::isfinite(o.delta.y) || !std::isfinite(o.delta.yaw)) return;
  // A scan's increment arrives after its interval (FusionFilter::add): it is the motion now, held from now.
  const Stamp at = std::max(t_, o.t1);
  last_motion_ = at;
  const MeanTwist v = mean_twist(o);
  vx_ = v.vx;
  vy_ = v.vy;
  r_ = v.yaw_rate;
  odometry_until_ = at + 2.0 * dt;  // until the next increment is overdue, speed and gyro wait
}

void ComplementaryFilter::on_map_pose(const MapPose& m) {
  if (!have_position_ || !heading_known_ || !std::isfinite(m.pose.x) || !std::isfinite(m.pose.y) ||
      !std::isfinite(m.pose.yaw) || !(m.sigma > 0) || !(m.yaw_sigma > 0))
    return;
  // No covariance to weigh it by: each of position and heading moves by the share the two σ give (a scalar Kalman
  // step), after a plausibility test at 4σ of both.
  const double sig = position_sigma();
  const Vec2 d(m.pose.x - pose_.x, m.pose.y - pose_.y);
  const double dyaw = wrap_angle(m.pose.yaw - pose_.yaw);
  if (d.norm() > 4.0 * std::hypot(sig, m.sigma) ||
      std::abs(dyaw) > 4.0 * std::hypot(std::sqrt(yaw_var_), m.yaw_sigma)) {
    ++out_.map_poses_rejected;
    return;
  }
  const double a = sig * sig / (sig * sig + m.sigma * m.sigma);
  pose_.x += a * d.x();
  pose_.y += a * d.y();
  sigma_fix_ = std::sqrt(1.0 / (1.0 / (sig * sig) + 1.0 / (m.sigma * m.sigma)));
  drift_since_fix_ = 0;
  const double ay = yaw_var_ / (yaw_var_ + m.yaw_sigma * m.yaw_sigma);
  pose_.yaw = wrap_angle(pose_.yaw + ay * dyaw);
  yaw_var_ *= 1.0 - ay;
  out_.last_map_pose = m.t;
}

double ComplementaryFilter::position_sigma() const {
  // The position lags GNSS by τ: a heading error δψ at speed v leaves it δψ·v·τ off the fixes; dead reckoning
  // since the last fix adds its drift.
  const double lag = std::sqrt(yaw_var_) * speed_ * cfg_.complementary.position_time_constant_s;
  const double drift = cfg_.complementary.drift_fraction * drift_since_fix_;
  return std::hypot(sigma_fix_, lag) + drift;
}

void ComplementaryFilter::correct(const GnssFix& f, double sigma) {
  const auto& c = cfg_.complementary;
  const double dt = last_fix_t_ < 0 ? 0.1 : std::clamp(f.t - last_fix_t_, 1e-3, 1.0);
  last_fix_t_ = f.t;
  const double nominal = gate_.nominal_sigma(f);
  const double w = std::pow(nominal / sigma, 2);  // a down-weighted fix pulls less
  // Position: GNSS low-passed, dead reckoning high-passed (first order, crossover 1/τ).
  const double ap = w * dt / (c.position_time_constant_s + dt);
  const Vec2 p(pose_.x, pose_.y);
  const Vec2 np = p + ap * (f.position - p);
  pose_.x = np.x();
  pose_.y = np.y();
  const double sig_now = sigma_fix_ + cfg_.complementary.drift_fraction * drift_since_fix_;
  sigma_fix_ = std::sqrt(std::pow((1 - ap) * sig_now, 2) + std::pow(ap * sigma, 2));
  drift_since_fix_ = 0;

  track_.push_back({f.t, f.position, dr_path_});
  while (!track_.empty() && f.t - track_.front().t > kTrackSpan) track_.pop_front();
  if (speed_ < cfg_.common.moving_speed) return;
  // Heading: the GNSS course over the last baseline against the dead-reckoned course over the same interval; the
  // same error, integrated, is the gyro's bias.
  for (auto it = track_.rbegin(); it != track_.rend(); ++it) {
    const Vec2 g = f.position - it->fix;
    if (g.norm() < c.course_baseline_m) continue;
    const Vec2 d = dr_path_ - it->dr;
    if (d.norm() < 0.5 * c.course_baseline_m) break;
    const double err = wrap_angle(std::atan2(g.y(), g.x()) - std::atan2(d.y(), d.x()));
    const double ah = w * dt / (c.heading_time_constant_s + dt);
    pose_.yaw = wrap_angle(pose_.yaw + ah * err);
    bias_ -= w * err * dt / (c.heading_time_constant_s * c.bias_time_constant_s);
    const double course_sigma = std::sqrt(2.0) * sigma / g.norm();
    yaw_var_ = std::pow(1 - ah, 2) * yaw_var_ + std::pow(ah * course_sigma, 2);
    break;
  }
  // Speed scale: the dead-reckoned chord over the GNSS chord, both over the last scale baseline.
  for (auto it = track_.rbegin(); it != track_.rend(); ++it) {
    const Vec2 g = f.position - it->fix;
    if (g.norm() < c.scale_baseline_m) continue;
    const double d = (dr_path_ - it->dr).norm();
    if (d < 0.5 * c.scale_baseline_m) break;
    const double ratio = std::clamp(d / g.norm(), 0.8, 1.25);
    scale_ *= 1.0 + w * (ratio - 1.0) * dt / c.scale_time_constant_s;
    break;
  }
}

void ComplementaryFilter::on_gnss(const GnssFix& f) {
  ++out_.gnss_counters.fixes;
  const auto reject = [this](GnssVerdict v) {
    out_.gnss = v;
    ++out_.gnss_counters.rejected;
    if (v == GnssVerdict::RejectedJump) ++out_.gnss_counters.jumps;
  };
  const bool quality_ok = f.fix_quality > 0 && f.fix_quality >= cfg_.gnss.min_fix_quality && f.position.allFinite();
  if (!have_position_) {
    if (!quality_ok) {
      reject(GnssVerdict::RejectedQuality);
      return;
    }
    pose_.x = f.position.x();
    pose_.y = f.position.y();
    sigma_fix_ = gate_.nominal_sigma(f);
    drift_since_fix_ = 0;
    last_fix_t_ = f.t;
    have_position_ = true;
    motion_since_fix_.setZero();
    gate_.check(f, t_, f.position, Eigen::Matrix2d::Identity() * sigma_fix_ * sigma_fix_, Vec2::Zero());
    out_.gnss = GnssVerdict::Accepted;
    out_.last_gnss_accepted = f.t;
    ++out_.gnss_counters.accepted;
    return;
  }
  if (!heading_known_ && f.heading_valid && std::isfinite(f.heading) && quality_ok) {
    // A dual-antenna receiver gives the heading at once, standing or not.
    pose_.yaw = wrap_angle(f.heading);
    yaw_var_ = std::pow(cfg_.common.initial_heading_sigma, 2);
    heading_known_ = true;
  }
  if (!heading_known_ && speed_ >= cfg_.common.standstill_speed) {
    out_.gnss = GnssVerdict::Waiting;
    if (speed_ < cfg_.common.moving_speed || !quality_ok) return;
    if (const auto off = heading_init_.add(f.position, Vec2(pose_.x, pose_.y))) {
      const Vec2 p = off->anchor_fix + Eigen::Rotation2Dd(off->yaw) * (Vec2(pose_.x, pose_.y) - off->anchor_dr);
      pose_ = Pose2{p.x(), p.y(), wrap_angle(pose_.yaw + off->yaw)};
      yaw_var_ = std::pow(cfg_.common.initial_heading_sigma, 2);
      sigma_fix_ = gate_.nominal_sigma(f);
      drift_since_fix_ = 0;
      heading_known_ = true;
      track_.clear();
      gate_.reset();
      motion_since_fix_.setZero();
      gate_.check(f, t_, p, Eigen::Matrix2d::Identity() * sigma_fix_ * sigma_fix_, Vec2::Zero());
    }
    return;
  }
  const double sig = position_sigma();
  const GnssCheck c =
      gate_.check(f, t_, Vec2(pose_.x, pose_.y), Eigen::Matrix2d::Identity() * sig * sig, motion_since_fix_);
  if (c.verdict != GnssVerdict::RejectedQuality && c.verdict != GnssVerdict::RejectedStale) motion_since_fix_.setZero();
  out_.gnss_nis = c.nis;
  if (!c.used()) {
    reject(c.verdict);
    return;
  }
  correct(f, c.sigma);
  if (f.heading_valid && std::isfinite(f.heading)) {
    // A dual-antenna heading, low-passed like the course.
    const double dt = 0.1;
    const double ah = dt / (cfg_.complementary.heading_time_constant_s + dt);
    pose_.yaw = wrap_angle(pose_.yaw + ah * wrap_angle(f.heading - pose_.yaw));
  }
  out_.gnss = c.verdict;
  out_.last_gnss_accepted = f.t;
  if (c.verdict == GnssVerdict::Accepted)
    ++out_.gnss_counters.accepted;
  else
    ++out_.gnss_counters.down_weighted;
}

void ComplementaryFilter::start_at(const Pose2& pose, double sigma, double yaw_sigma) {
  pose_ = Pose2{pose.x, pose.y, wrap_angle(pose.yaw)};
  sigma_fix_ = sigma;
  drift_since_fix_ = 0;
  yaw_var_ = yaw_sigma * yaw_sigma;
  have_position_ = heading_known_ = true;
  motion_since_fix_.setZero();
}

void ComplementaryFilter::relocate(const Pose2& map_from_estimate) {
  pose_ = map_from_estimate * pose_;
  pose_.yaw = wrap_angle(pose_.yaw);
}

LocalizationState ComplementaryFilter::state() const {
  LocalizationState s = out_;
  s.stamp = t_;
  s.initialised = have_position_ && heading_known_;
  s.pose = pose_;
  s.vx = vx_;
  s.vy = vy_;
  s.yaw_rate = r_;
  s.gyro_bias = bias_;
  s.speed_scale = scale_;
  const double sig = position_sigma();
  s.covariance = Eigen::Vector3d(sig * sig, sig * sig, yaw_var_).asDiagonal();
  s.quality = assess_quality(s, last_motion_, cfg_.common);
  return s;
}

}  // namespace fsd::fusion
