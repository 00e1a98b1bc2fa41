#include "localization/fusion/fusion_filter.hpp"

#include <cmath>
#include <stdexcept>

#include <Eigen/Eigenvalues>

#include "localization/fusion/complementary_filter.hpp"
#include "localization/fusion/ekf_filter.hpp"

namespace fsd::fusion {

MeanTwist mean_twist(const OdometryIncrement& o) {
  const double dt = o.t1 - o.t0;
  const Vec2 v = Eigen::Rotation2Dd(-0.5 * o.delta.yaw) * Vec2(o.delta.x, o.delta.y) / dt;
  return {v.x(), v.y(), o.delta.yaw / dt};
}

Stamp stamp_of(const Measurement& m) {
  return std::visit(
      [](const auto& v) -> Stamp {
        if constexpr (std::is_same_v<std::decay_t<decltype(v)>, OdometryIncrement>) {
          return v.t1;
        } else {
          return v.t;
        }
      },
      m);
}

void FusionFilter::add(const Measurement& m) {
  constexpr double kOutOfOrder = 1e-3;  // s: reordering below this is applied at the filter's time
  const Stamp t = stamp_of(m);
  if (!std::isfinite(t)) return;
  if (!started_) {
    started_ = true;
    t_ = t;
  }
  // A GNSS fix goes to the gate, which judges its age; a LiDAR increment (a scan is complete only when the next one
  // starts, and processed after) is the mean motion over its interval, taken at the filter's time. Anything else
  // older than the filter's time is dropped.
  const bool late_allowed = std::holds_alternative<GnssFix>(m) || std::holds_alternative<OdometryIncrement>(m);
  if (t < t_ - kOutOfOrder && !late_allowed) {
    ++dropped_;
    return;
  }
  advance(t);
  std::visit(
      [this](const auto& v) {
        using T = std::decay_t<decltype(v)>;
        if constexpr (std::is_same_v<T, ImuSample>)
          on_imu(v);
        else if constexpr (std::is_same_v<T, BodySpeed>)
          on_speed(v);
        else if constexpr (std::is_same_v<T, GnssFix>)
          on_gnss(v);
        else if constexpr (std::is_same_v<T, MapPose>)
          on_map_pose(v);
        else
          on_odometry(v);
      },
      m);
}

std::string_view to_string(Quality q) {
  switch (q) {
    case Quality::Good:
      return "good";
    case Quality::Degraded:
      return "degraded";
    case Quality::Lost:
      return "lost";
  }
  return "lost";
}

std::string_view to_string(GnssVerdict v) {
  switch (v) {
    case GnssVerdict::None:
      return "none";
    case GnssVerdict::Accepted:
      return "accepted";
    case GnssVerdict::DownWeighted:
      return "down_weighted";
    case GnssVerdict::RejectedQuality:
      return "rejected_quality";
    case GnssVerdict::RejectedStale:
      return "rejected_stale";
    case GnssVerdict::RejectedInnovation:
      return "rejected_innovation";
    case GnssVerdict::RejectedJump:
      return "rejected_jump";
    case GnssVerdict::Waiting:
      return "waiting";
  }
  return "none";
}

double LocalizationState::position_sigma() const {
  const Eigen::Matrix2d P = covariance.topLeftCorner<2, 2>();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(P, Eigen::EigenvaluesOnly);
  return std::sqrt(std::max(0.0, es.eigenvalues().maxCoeff()));
}

Quality assess_quality(const LocalizationState& s, Stamp last_motion, const FusionCommonConfig& cfg) {
  const double sigma = s.position_sigma();
  if (!s.initialised || !std::isfinite(sigma) || sigma > cfg.lost_sigma_m ||
      s.stamp - last_motion > cfg.motion_timeout_s)
    return Quality::Lost;
  const bool recent_fix = s.last_gnss_accepted >= 0 && s.stamp - s.last_gnss_accepted <= cfg.good_gnss_timeout_s;
  return recent_fix && sigma <= cfg.good_sigma_m ? Quality::Good : Quality::Degraded;
}

std::unique_ptr<FusionFilter> make_fusion_filter(const std::string& name, const FusionConfig& cfg) {
  if (name == "ekf") return std::make_unique<EkfFilter>(cfg);
  if (name == "complementary") return std::make_unique<ComplementaryFilter>(cfg);
  throw std::invalid_argument("unknown fusion filter '" + name + "' (ekf | complementary)");
}

}  // namespace fsd::fusion
