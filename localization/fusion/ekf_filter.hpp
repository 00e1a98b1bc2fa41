#pragma once
// The EKF of the fusion (issue #17). State (map frame, body velocity at the reference point):
//   x, y, yaw, vx, vy, yaw rate r, gyro bias b, optical speed scale k, rear slip compliance c.
// Between measurements a constant-velocity, constant-turn model (vx, vy, r random walks); each gyro sample
// measures r + b, each optical sample k·(v + r × lever), the wheels vx + r × lever (only while no optical sample
// comes), a LiDAR odometry increment the mean (vx, vy, r) over its interval (against the filter's own mean over that
// interval: it arrives a scan's processing after it, when a turn-in has moved r on), a GNSS fix the position (through
// the gate) and, when the receiver gives one, its velocity over ground (vx, vy + r·lx rotated: the sideslip). A
// standing car is held to r = 0, so the gyro's bias shows at once; GNSS while driving makes the bias
// and the speed scale observable, which is what keeps dead reckoning through an outage well under the raw
// sensors' drift.
#include <deque>
#include <limits>
#include <optional>

#include <Eigen/Core>

#include "localization/fusion/fusion_filter.hpp"
#include "localization/fusion/gnss_gate.hpp"
#include "localization/fusion/heading_init.hpp"

namespace fsd::fusion {

class EkfFilter final : public FusionFilter {
 public:
  static constexpr int kN = 9;
  enum Index { X = 0, Y, Yaw, Vx, Vy, R, Bias, Scale, Slip };
  using Vec = Eigen::Matrix<double, kN, 1>;
  using Mat = Eigen::Matrix<double, kN, kN>;
  // What a measurement of the motion leaves alone. Only absolute measurements (fixes, headings, map poses) move the
  // position; the motion moves it through the prediction. Without satellites the position's variance grows, and
  // with it its correlation with the heading and the velocities, over a lever as long as the distance driven since
  // the start: an innovation of the yaw rate then moved the pose sideways by decimetres at every scan (20 m per
  // radian), enough to hit cones in lap 1. The gyro and the LiDAR increments still turn the yaw (its error over the
  // last samples is theirs to correct: held off, the yaw integrated the filtered rate's lag at every turn-in); the
  // wheels, the standstill and the kinematic yaw rate, rougher, move neither.
  static constexpr unsigned kPosition = (1u << X) | (1u << Y);
  static constexpr unsigned kPose = kPosition | (1u << Yaw);

  explicit EkfFilter(const FusionConfig& cfg = {});
  void start_at(const Pose2& pose, double sigma, double yaw_sigma) override;
  void relocate(const Pose2& map_from_estimate) override;
  LocalizationState state() const override;
  std::string_view name() const override { return "ekf"; }

 private:
  void advance(Stamp t) override { predict(t); }
  void predict(Stamp t);
  // The measurement z of prediction h; returns its normalised innovation squared (NIS), and applies it only when
  // that is at most `gate`. `consider`: the states this update must not move (a mask of 1 << Index).
  template <int M>
  double update(const Eigen::Matrix<double, M, 1>& z, const Eigen::Matrix<double, M, 1>& h,
                const Eigen::Matrix<double, M, kN>& H, const Eigen::Matrix<double, M, M>& Rm, unsigned consider = 0,
                double gate = std::numeric_limits<double>::infinity());
  void on_imu(const ImuSample& s) override;
  void on_speed(const BodySpeed& s) override;
  void on_gnss(const GnssFix& f) override;
  void on_gnss_velocity(const GnssFix& f);
  void on_odometry(const OdometryIncrement& o) override;
  void on_map_pose(const MapPose& m) override;
  void apply_heading(const HeadingInitialiser::Offset& off, double fix_sigma);
  // The mean (vx, vy, r) the prediction carried over [t0, t1]; empty when the steps held do not reach back to t0.
  std::optional<Eigen::Vector3d> held_twist(Stamp t0, Stamp t1) const;

  // The velocities each prediction step carried, over the last second (bounded): what an increment of an interval
  // now past is compared with.
  struct HeldTwist {
    Stamp from, to;
    Eigen::Vector3d twist;  // vx, vy, r
  };
  std::deque<HeldTwist> held_;

  FusionConfig cfg_;
  GnssGate gate_;
  HeadingInitialiser heading_init_;
  Vec x_ = Vec::Zero();
  Mat P_ = Mat::Zero();
  bool have_position_ = false;
  bool heading_known_ = false;
  double speed_ = 0;  // latest measured ground speed (m/s), for standstill and moving tests
  Stamp last_motion_ = -1e300, last_optical_ = -1e300;
  Stamp last_gyro_ = -1e300;
  Stamp heading_rejected_since_ = -1;     // first of the receiver headings rejected in a row (-1: none)
  Vec2 motion_since_fix_ = Vec2::Zero();  // dead-reckoned displacement since the previous fix (jump test)
  LocalizationState out_;                 // GNSS verdicts and counters
};

}  // namespace fsd::fusion
