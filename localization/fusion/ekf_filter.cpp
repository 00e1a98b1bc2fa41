#include "localization/fusion/ekf_filter.hpp"

#include <cmath>
#include <numbers>

namespace fsd::fusion {

namespace {}

EkfFilter::EkfFilter(const FusionConfig& cfg)
    : cfg_(cfg), gate_(cfg.gnss), heading_init_(cfg.common.heading_baseline_m) {
  x_(Scale) = 1.0;
  // Position unknown until the first fix; the heading is provisional (0, small σ) until the GNSS track gives it,
  // so the linearisation never sees an arbitrary heading with a huge variance.
  P_.diagonal() << 1e6, 1e6, 1e-4, 1.0, 1.0, 0.1, std::pow(cfg.ekf.initial_bias_sigma, 2),
      std::pow(cfg.ekf.initial_scale_sigma, 2), std::pow(cfg.ekf.initial_slip_sigma, 2);
}

void EkfFilter::predict(Stamp t) {
  const double dt = t - t_;
  if (dt <= 0) return;
  const double yaw = x_(Yaw), vx = x_(Vx), vy = x_(Vy), r = x_(R);
  constexpr double kHeldFor = 1.0;        // s: well beyond an increment's interval and its processing
  constexpr std::size_t kHeldMax = 4096;  // steps: the bound whatever the measurement rate
  held_.push_back({t_, t, Eigen::Vector3d(vx, vy, r)});
  while (held_.size() > kHeldMax || (!held_.empty() && held_.front().to < t - kHeldFor)) held_.pop_front();
  t_ = t;
  const double ym = yaw + 0.5 * r * dt;  // midpoint heading
  const double c = std::cos(ym), s = std::sin(ym);
  const Vec2 step{dt * (vx * c - vy * s), dt * (vx * s + vy * c)};
  x_(X) += step.x();
  x_(Y) += step.y();
  x_(Yaw) = wrap_angle(yaw + r * dt);
  motion_since_fix_ += step;

  Mat F = Mat::Identity();
  F(X, Yaw) = -step.y();
  F(Y, Yaw) = step.x();
  F(X, R) = -step.y() * 0.5 * dt;
  F(Y, R) = step.x() * 0.5 * dt;
  F(X, Vx) = dt * c;
  F(X, Vy) = -dt * s;
  F(Y, Vx) = dt * s;
  F(Y, Vy) = dt * c;
  F(Yaw, R) = dt;
  const auto& e = cfg_.ekf;
  Mat Q = Mat::Zero();
  Q(X, X) = Q(Y, Y) = e.position_noise * e.position_noise * dt;
  Q(Vx, Vx) = Q(Vy, Vy) = e.accel_noise * e.accel_noise * dt;
  Q(R, R) = e.yaw_accel_noise * e.yaw_accel_noise * dt;
  Q(Bias, Bias) = e.bias_walk * e.bias_walk * dt;
  Q(Scale, Scale) = e.scale_walk * e.scale_walk * dt;
  Q(Slip, Slip) = e.slip_walk * e.slip_walk * dt;
  P_ = F * P_ * F.transpose() + Q;
}

template <int M>
double EkfFilter::update(const Eigen::Matrix<double, M, 1>& z, const Eigen::Matrix<double, M, 1>& h,
                         const Eigen::Matrix<double, M, kN>& H, const Eigen::Matrix<double, M, M>& Rm,
                         unsigned consider, double gate) {
  const Eigen::Matrix<double, M, 1> nu = z - h;  // no angles here: heading residuals come in wrapped
  const Eigen::Matrix<double, M, M> S = H * P_ * H.transpose() + Rm;
  const Eigen::Matrix<double, M, M> S_inv = S.inverse();
  const double nis = nu.dot(S_inv * nu);
  if (nis > gate) return nis;
  Eigen::Matrix<double, kN, M> K = P_ * H.transpose() * S_inv;
  for (int i = 0; i < kN; ++i)
    if (consider & (1u << i)) K.row(i).setZero();
  x_ += K * nu;
  x_(Yaw) = wrap_angle(x_(Yaw));
  // Joseph form: stays symmetric positive definite with the many small updates of a 200 Hz gyro.
  const Mat IKH = Mat::Identity() - K * H;
  P_ = IKH * P_ * IKH.transpose() + K * Rm * K.transpose();
  return nis;
}

void EkfFilter::on_imu(const ImuSample& s) {
  if (!std::isfinite(s.gyro.z())) return;
  last_motion_ = s.t;
  last_gyro_ = s.t;
  Eigen::Matrix<double, 1, kN> H = Eigen::Matrix<double, 1, kN>::Zero();
  H(0, R) = 1.0;
  H(0, Bias) = 1.0;
  const double g = cfg_.ekf.gyro_sigma;
  update<1>(Eigen::Matrix<double, 1, 1>(s.gyro.z()), Eigen::Matrix<double, 1, 1>(x_(R) + x_(Bias)), H,
            Eigen::Matrix<double, 1, 1>(g * g), kPosition);
}

void EkfFilter::on_speed(const BodySpeed& s) {
  if (!std::isfinite(s.vx) || (s.has_vy && !std::isfinite(s.vy))) return;
  // The wheels are the fallback: they slip, and their rpm-to-speed factor is only nominal; where the optical
  // sensor reports, they would pull its scale estimate to that factor.
  if (s.source == BodySpeed::Source::Optical)
    last_optical_ = s.t;
  else if (s.t - last_optical_ < 0.2)
    return;
  last_motion_ = s.t;
  speed_ = s.has_vy ? std::hypot(s.vx, s.vy) : std::abs(s.vx);
  const double lx = s.lever.x(), ly = s.lever.y();
  const double vx = x_(Vx), vy = x_(Vy), r = x_(R);
  if (s.source == BodySpeed::Source::Optical) {
    // The sensor's velocity: v + r × lever = (vx − r·ly, vy + r·lx), read through the scale k. The speed
    // samples alone cannot tell a faster car from a larger scale: k is a consider state here (its gain held at
    // zero, its correlation with vx kept), learnt only from what GNSS says of the distance driven. Updating it
    // here let it wander with every acceleration (the product k·vx is not linear).
    const double k = x_(Scale);
    const double sx = vx - r * ly, sy = vy + r * lx;
    const double sig2 = cfg_.ekf.optical_sigma * cfg_.ekf.optical_sigma;
    if (s.has_vy) {
      Eigen::Matrix<double, 2, kN> H = Eigen::Matrix<double, 2, kN>::Zero();
      H(0, Vx) = k;
      H(0, R) = -k * ly;
      H(0, Scale) = sx;
      H(1, Vy) = k;
      H(1, R) = k * lx;
      H(1, Scale) = sy;
      update<2>(Eigen::Vector2d(s.vx, s.vy), Eigen::Vector2d(k * sx, k * sy), H, Eigen::Matrix2d::Identity() * sig2,
                kPose | (1u << Scale));
    } else {
      Eigen::Matrix<double, 1, kN> H = Eigen::Matrix<double, 1, kN>::Zero();
      H(0, Vx) = k;
      H(0, R) = -k * ly;
      H(0, Scale) = sx;
      update<1>(Eigen::Matrix<double, 1, 1>(s.vx), Eigen::Matrix<double, 1, 1>(k * sx), H,
                Eigen::Matrix<double, 1, 1>(sig2), kPose | (1u << Scale));
    }
  } else {
    // Without an optical sensor nothing measures vy: the car's own kinematics do. The rear axle slides outwards
    // by its tyres' slip angle, which grows with the lateral acceleration: vy = c·vx·|vx|·(−r), c the rear slip
    // compliance (rad per m/s²), learnt while GNSS measures the velocity and heading (0.8 m/s at the limit on the
    // virtual car). Holding vy to 0 instead put a sliding car's slip into its yaw, or, with the heading measured,
    // made the pose drift sideways by the slip as soon as the fix went. Without that row at all the velocity's
    // covariance, and with it the position's, grew by metres a second whenever GNSS was rejected.
    const double sig = cfg_.ekf.wheel_sigma + cfg_.ekf.wheel_sigma_fraction * std::abs(s.vx);
    const double lat = cfg_.ekf.wheel_lateral_sigma;
    const double c = x_(Slip), vv = vx * std::abs(vx);
    Eigen::Matrix<double, 2, kN> H = Eigen::Matrix<double, 2, kN>::Zero();
    H(0, Vx) = 1.0;
    H(0, R) = -ly;
    H(1, Vy) = 1.0;
    H(1, R) = lx + c * vv;
    H(1, Vx) = 2.0 * c * std::abs(vx) * r;
    H(1, Slip) = vv * r;
    update<2>(Eigen::Vector2d(s.vx, 0.0), Eigen::Vector2d(vx - r * ly, vy + r * lx + c * vv * r), H,
              Eigen::Vector2d(sig * sig, lat * lat).asDiagonal().toDenseMatrix(), kPose);
  }
  // No gyro for a while (the GNSS-INS, the car's only one, fell silent): the wheels' kinematic yaw rate stands in,
  // loosely. Without it the yaw rate lived on the LiDAR increments alone, a scan behind the turn, and the scans'
  // deskew lost the car's turn.
  constexpr double kGyroStale = 0.1;  // s
  if (s.source == BodySpeed::Source::Wheels && std::isfinite(s.kinematic_yaw_rate) && s.t - last_gyro_ > kGyroStale) {
    const double sig =
        cfg_.ekf.kinematic_rate_sigma + cfg_.ekf.kinematic_rate_fraction * std::abs(s.kinematic_yaw_rate);
    Eigen::Matrix<double, 1, kN> H = Eigen::Matrix<double, 1, kN>::Zero();
    H(0, R) = 1.0;
    update<1>(Eigen::Matrix<double, 1, 1>(s.kinematic_yaw_rate), Eigen::Matrix<double, 1, 1>(x_(R)), H,
              Eigen::Matrix<double, 1, 1>(sig * sig), kPose);
  }
  if (speed_ < cfg_.common.standstill_speed) {
    // A standing car neither turns nor moves: what the gyro reads is its bias. Held only by the wheels' loose row
    // (0.3 m/s), the speed of a standing car followed the GNSS fixes' noise to 0.08 m/s, and the supervisor's
    // standstill (0.1 m/s for 0.5 s), which AS Finished waits for, came seconds late or never.
    Eigen::Matrix<double, 3, kN> H = Eigen::Matrix<double, 3, kN>::Zero();
    H(0, R) = 1.0;
    H(1, Vx) = 1.0;
    H(2, Vy) = 1.0;
    const double rs = cfg_.ekf.standstill_rate_sigma;
    update<3>(Eigen::Vector3d::Zero(), Eigen::Vector3d(x_(R), x_(Vx), x_(Vy)), H,
              Eigen::Vector3d(rs * rs, 1e-4, 1e-4).asDiagonal().toDenseMatrix(), kPose);
  }
}

void EkfFilter::on_odometry(const OdometryIncrement& o) {
  const double dt = o.t1 - o.t0;
  if (!(dt > 1e-3) || !std::isfinite(o.delta.x) || !std::isfinite(o.delta.y) || !std::isfinite(o.delta.yaw) ||
      !o.covariance.allFinite())
    return;
  last_motion_ = std::max(last_motion_, o.t1);
  const MeanTwist v = mean_twist(o);
  // Compared with what the filter carried over the same interval, not with the velocities now: its mean lies half
  // an interval (and a scan's processing) back, and at a turn-in r has moved on since (read as now, the increment
  // would pull r back and the yaw lag: 2.4 times the yaw error through a slalom). Its error is taken to be the one
  // of the velocities now, which holds while it comes less than half its interval late (the gyro's samples have
  // corrected r by then; the Stack's processing takes milliseconds).
  const Eigen::Vector3d then = held_twist(o.t0, o.t1).value_or(Eigen::Vector3d(x_(Vx), x_(Vy), x_(R)));
  Eigen::Matrix<double, 3, kN> H = Eigen::Matrix<double, 3, kN>::Zero();
  H(0, Vx) = 1.0;
  H(1, Vy) = 1.0;
  H(2, R) = 1.0;
  Eigen::Matrix3d Rm = o.covariance / (dt * dt);
  Rm += Eigen::Matrix3d::Identity() * 1e-8;
  // A registration that slipped (few cones, a degenerate scan) claims a motion the wheels and the gyro deny, with a
  // covariance that does not know it: gated like GNSS, at χ²(3 dof) 99.9 %, so one bad scan cannot turn the heading.
  constexpr double kGate = 16.27;
  const double nis = update<3>(Eigen::Vector3d(v.vx, v.vy, v.yaw_rate), then, H, Rm, kPosition, kGate);
  if (nis > kGate) ++out_.odometry_rejected;
}

std::optional<Eigen::Vector3d> EkfFilter::held_twist(Stamp t0, Stamp t1) const {
  if (held_.empty() || held_.front().from > t0 || !(t1 > t0)) return std::nullopt;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  double covered = 0;
  for (const auto& h : held_) {
    const double a = std::max(h.from, t0), b = std::min(h.to, t1);
    if (b <= a) continue;
    sum += (b - a) * h.twist;
    covered += b - a;
  }
  if (covered < 0.5 * (t1 - t0)) return std::nullopt;
  return sum / covered;
}

void EkfFilter::on_map_pose(const MapPose& m) {
  if (!have_position_ || !heading_known_ || !std::isfinite(m.pose.x) || !std::isfinite(m.pose.y) ||
      !std::isfinite(m.pose.yaw) || !(m.sigma > 0) || !(m.yaw_sigma > 0))
    return;
  Eigen::Matrix<double, 3, kN> H = Eigen::Matrix<double, 3, kN>::Zero();
  H(0, X) = 1.0;
  H(1, Y) = 1.0;
  H(2, Yaw) = 1.0;
  const double nu_yaw = wrap_angle(m.pose.yaw - x_(Yaw));
  const Eigen::Vector3d sig2(m.sigma * m.sigma, m.sigma * m.sigma, m.yaw_sigma * m.yaw_sigma);
  // A match that paired the wrong cones claims a pose the dead reckoning denies: gated at χ²(3 dof) 99.9 %.
  constexpr double kGate = 16.27;
  const double nis = update<3>(Eigen::Vector3d(m.pose.x, m.pose.y, x_(Yaw) + nu_yaw),
                               Eigen::Vector3d(x_(X), x_(Y), x_(Yaw)), H, sig2.asDiagonal().toDenseMatrix(), 0, kGate);
  if (nis > kGate)
    ++out_.map_poses_rejected;
  else
    out_.last_map_pose = m.t;
}

void EkfFilter::apply_heading(const HeadingInitialiser::Offset& off, double fix_sigma) {
  const Eigen::Rotation2Dd rot(off.yaw);
  const Vec2 p = off.anchor_fix + rot * (Vec2(x_(X), x_(Y)) - off.anchor_dr);
  x_(X) = p.x();
  x_(Y) = p.y();
  x_(Yaw) = wrap_angle(x_(Yaw) + off.yaw);
  for (int i : {X, Y, Yaw}) {
    P_.row(i).setZero();
    P_.col(i).setZero();
  }
  P_(X, X) = P_(Y, Y) = fix_sigma * fix_sigma;
  P_(Yaw, Yaw) = std::pow(cfg_.common.initial_heading_sigma, 2);
  heading_known_ = true;
  gate_.reset();
}

void EkfFilter::on_gnss(const GnssFix& f) {
  ++out_.gnss_counters.fixes;
  const auto reject = [this](GnssVerdict v) {
    out_.gnss = v;
    ++out_.gnss_counters.rejected;
    if (v == GnssVerdict::RejectedJump) ++out_.gnss_counters.jumps;
  };
  if (!have_position_) {
    if (f.fix_quality <= 0 || f.fix_quality < cfg_.gnss.min_fix_quality || !f.position.allFinite()) {
      reject(GnssVerdict::RejectedQuality);
      return;
    }
    const double sig = gate_.nominal_sigma(f);
    x_(X) = f.position.x();
    x_(Y) = f.position.y();
    P_(X, X) = P_(Y, Y) = sig * sig;
    P_.block<2, kN - 2>(0, 2).setZero();
    P_.block<kN - 2, 2>(2, 0).setZero();
    have_position_ = true;
    motion_since_fix_.setZero();
    gate_.check(f, t_, f.position, P_.topLeftCorner<2, 2>(), Vec2::Zero());  // the gate's previous fix
    out_.gnss = GnssVerdict::Accepted;
    out_.last_gnss_accepted = f.t;
    ++out_.gnss_counters.accepted;
    return;
  }
  if (!heading_known_ && f.heading_valid && std::isfinite(f.heading) && f.fix_quality > 0) {
    // A dual-antenna receiver gives the heading at once, standing or not.
    P_.row(Yaw).setZero();
    P_.col(Yaw).setZero();
    x_(Yaw) = wrap_angle(f.heading);
    P_(Yaw, Yaw) = std::pow(cfg_.common.initial_heading_sigma, 2);
    heading_known_ = true;
  }
  if (!heading_known_ && speed_ >= cfg_.common.standstill_speed) {
    // Moving without a heading: the fix goes to the heading initialisation, not into the state.
    if (speed_ < cfg_.common.moving_speed || f.fix_quality < cfg_.gnss.min_fix_quality || f.fix_quality <= 0) {
      out_.gnss = GnssVerdict::Waiting;
      return;
    }
    out_.gnss = GnssVerdict::Waiting;
    if (const auto off = heading_init_.add(f.position, Vec2(x_(X), x_(Y)))) {
      apply_heading(*off, gate_.nominal_sigma(f));
      motion_since_fix_.setZero();
      gate_.check(f, t_, Vec2(x_(X), x_(Y)), P_.topLeftCorner<2, 2>(), Vec2::Zero());
    }
    return;
  }
  if (f.velocity_valid) on_gnss_velocity(f);
  const GnssCheck c = gate_.check(f, t_, Vec2(x_(X), x_(Y)), P_.topLeftCorner<2, 2>(), motion_since_fix_);
  if (c.verdict != GnssVerdict::RejectedQuality && c.verdict != GnssVerdict::RejectedStale) motion_since_fix_.setZero();
  out_.gnss_nis = c.nis;
  if (!c.used()) {
    reject(c.verdict);
    return;
  }
  Eigen::Matrix<double, 2, kN> H = Eigen::Matrix<double, 2, kN>::Zero();
  H(0, X) = 1.0;
  H(1, Y) = 1.0;
  update<2>(f.position, Vec2(x_(X), x_(Y)), H, Eigen::Matrix2d::Identity() * c.sigma * c.sigma);
  if (f.heading_valid && std::isfinite(f.heading) && heading_known_) {
    // The receiver's heading at its own accuracy: weighted as loosely as the heading from the GNSS track (3°), the
    // yaw followed the course over ground instead, off by the sideslip the wheels' row does not see (1.3° round a
    // skid pad, 0.17 m on a cone 8 m away). A heading the dead reckoning denies (χ², 1 dof, 99.9 %) is turned away,
    // unless the receiver has insisted on it for as long as the position gate waits before it recovers.
    constexpr double kGate = 10.83;
    const double sigma =
        f.heading_sigma > 0 && std::isfinite(f.heading_sigma) ? f.heading_sigma : cfg_.gnss.heading_sigma;
    const bool insisted = heading_rejected_since_ >= 0 && f.t - heading_rejected_since_ >= cfg_.gnss.recover_after_s;
    Eigen::Matrix<double, 1, kN> Hh = Eigen::Matrix<double, 1, kN>::Zero();
    Hh(0, Yaw) = 1.0;
    const double nu = wrap_angle(f.heading - x_(Yaw));
    const double nis = update<1>(Eigen::Matrix<double, 1, 1>(x_(Yaw) + nu), Eigen::Matrix<double, 1, 1>(x_(Yaw)), Hh,
                                 Eigen::Matrix<double, 1, 1>(sigma * sigma), 0,
                                 insisted ? std::numeric_limits<double>::infinity() : kGate);
    if (nis > kGate && !insisted) {
      ++out_.headings_rejected;
      if (heading_rejected_since_ < 0) heading_rejected_since_ = f.t;
    } else {
      heading_rejected_since_ = -1;
    }
  }
  out_.gnss = c.verdict;
  out_.last_gnss_accepted = f.t;
  if (c.verdict == GnssVerdict::Accepted)
    ++out_.gnss_counters.accepted;
  else
    ++out_.gnss_counters.down_weighted;
}

void EkfFilter::on_gnss_velocity(const GnssFix& f) {
  // The receiver's velocity over ground (Doppler), at lever (lx, 0) ahead of the reference point: rotated into the
  // body it is (vx, vy + r·lx). It measures vy, which the wheels cannot: without it the wheels' row holds vy near 0
  // and a sliding car leaves the filter behind, its fixes rejected as multipath until the gate recovers.
  // Taken by itself, before the position's gate: Doppler is not what multipath shifts.
  if (!cfg_.ekf.gnss_velocity || !heading_known_ || f.fix_quality <= 0 || f.fix_quality < cfg_.gnss.min_fix_quality ||
      !f.velocity.allFinite() || f.velocity.norm() < cfg_.common.moving_speed)
    return;
  const double c = std::cos(x_(Yaw)), s = std::sin(x_(Yaw)), lx = cfg_.ekf.gnss_velocity_lever_x;
  const double bx = x_(Vx), by = x_(Vy) + x_(R) * lx;
  Eigen::Matrix<double, 2, kN> H = Eigen::Matrix<double, 2, kN>::Zero();
  H(0, Yaw) = -s * bx - c * by;
  H(1, Yaw) = c * bx - s * by;
  H(0, Vx) = c;
  H(1, Vx) = s;
  H(0, Vy) = -s;
  H(1, Vy) = c;
  H(0, R) = -s * lx;
  H(1, R) = c * lx;
  const Vec2 h(c * bx - s * by, s * bx + c * by);
  const double sig2 = cfg_.ekf.gnss_velocity_sigma * cfg_.ekf.gnss_velocity_sigma;
  update<2>(f.velocity, h, H, Eigen::Matrix2d::Identity() * sig2, 0, cfg_.ekf.gnss_velocity_gate);
}

void EkfFilter::start_at(const Pose2& pose, double sigma, double yaw_sigma) {
  x_(X) = pose.x;
  x_(Y) = pose.y;
  x_(Yaw) = wrap_angle(pose.yaw);
  for (int i : {X, Y, Yaw}) {
    P_.row(i).setZero();
    P_.col(i).setZero();
  }
  P_(X, X) = P_(Y, Y) = sigma * sigma;
  P_(Yaw, Yaw) = yaw_sigma * yaw_sigma;
  have_position_ = heading_known_ = true;
  motion_since_fix_.setZero();
}

void EkfFilter::relocate(const Pose2& map_from_estimate) {
  const Pose2 p = map_from_estimate * Pose2{x_(X), x_(Y), x_(Yaw)};
  x_(X) = p.x;
  x_(Y) = p.y;
  x_(Yaw) = wrap_angle(p.yaw);
  // The position's uncertainty turns with the frame; the yaw's and the rest are unchanged.
  Mat J = Mat::Identity();
  J.block<2, 2>(X, X) = Eigen::Rotation2Dd(map_from_estimate.yaw).toRotationMatrix();
  P_ = J * P_ * J.transpose();
}

LocalizationState EkfFilter::state() const {
  LocalizationState s = out_;
  s.stamp = t_;
  s.initialised = have_position_ && heading_known_;
  s.pose = Pose2{x_(X), x_(Y), x_(Yaw)};
  s.vx = x_(Vx);
  s.vy = x_(Vy);
  s.yaw_rate = x_(R);
  s.gyro_bias = x_(Bias);
  s.speed_scale = x_(Scale);
  s.covariance = P_.topLeftCorner<3, 3>();
  s.quality = assess_quality(s, last_motion_, cfg_.common);
  return s;
}

}  // namespace fsd::fusion
