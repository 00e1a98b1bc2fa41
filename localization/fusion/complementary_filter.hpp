#pragma once
// The paper's complementary filter (§III-A-2): the car's motion from odometry (gyro and ground speed, or LiDAR
// odometry increments when they arrive) is integrated at the sensors' rate and passes at high frequency; GNSS
// pulls the integrated pose back at low frequency, so dead reckoning's drift and GNSS noise cancel at the
// crossover 1/τ. Beyond the paper, two slow integrals keep the dead reckoning honest for an outage: the gyro bias
// (from the heading's pull to the GNSS course, and at standstill straight from the gyro) and the optical speed
// scale (GNSS chord length against the dead-reckoned chord). Its covariance is a model, not a propagation: the
// position σ grows with the distance driven since the last fix and shrinks as fixes come in.
#include <deque>

#include "localization/fusion/fusion_filter.hpp"
#include "localization/fusion/gnss_gate.hpp"
#include "localization/fusion/heading_init.hpp"

namespace fsd::fusion {

class ComplementaryFilter final : public FusionFilter {
 public:
  explicit ComplementaryFilter(const FusionConfig& cfg = {});
  void start_at(const Pose2& pose, double sigma, double yaw_sigma) override;
  void relocate(const Pose2& map_from_estimate) override;
  LocalizationState state() const override;
  std::string_view name() const override { return "complementary"; }

 private:
  void advance(Stamp t) override;  // dead reckoning to t
  void on_imu(const ImuSample& s) override;
  void on_speed(const BodySpeed& s) override;
  void on_odometry(const OdometryIncrement& o) override;
  void on_map_pose(const MapPose& m) override;
  void on_gnss(const GnssFix& f) override;
  void correct(const GnssFix& f, double sigma);
  double position_sigma() const;

  struct Track {  // an accepted fix and the dead-reckoned path's end at the same instant
    Stamp t;
    Vec2 fix;
    Vec2 dr;
  };

  FusionConfig cfg_;
  GnssGate gate_;
  HeadingInitialiser heading_init_;
  Pose2 pose_;
  double vx_ = 0, vy_ = 0, r_ = 0, bias_ = 0, scale_ = 1.0;
  Stamp last_fix_t_ = -1, odometry_until_ = -1e300;
  bool have_position_ = false, heading_known_ = false;
  double speed_ = 0;
  double sigma_fix_ = 1e3, drift_since_fix_ = 0;  // position σ at the last fix, and travel since
  double yaw_var_ = 1e-4;
  Vec2 dr_path_ = Vec2::Zero();  // the motion alone, summed without GNSS corrections
  Vec2 motion_since_fix_ = Vec2::Zero();
  std::deque<Track> track_;
  Stamp last_motion_ = -1e300, last_optical_ = -1e300;
  LocalizationState out_;
};

}  // namespace fsd::fusion
