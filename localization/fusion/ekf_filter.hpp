#pragma once
// The EKF of the fusion (issue #17). State (map frame, body velocity at the reference point):
//   x, y, yaw, vx, vy, yaw rate r, gyro bias b, optical speed scale k, rear slip compliance c.
// Between measurements a constant-velocity, constant-turn model (vx, vy, r random walks); each gyro sample
// measures r + b, each optical sample k·(v + r × lever), the wheels vx + r × lever (only while no optical sample
// comes), a LiDAR odometry increment the mean (vx, vy, r) over its interval, a GNSS fix the position (through
// the gate) and, when the receiver gives one, its velocity over ground (vx, vy + r·lx rotated: the sideslip). A
// standing car is held to r = 0, so the gyro's bias shows at once; GNSS while driving makes the bias
// and the speed scale observable, which is what keeps dead reckoning through an outage well under the raw
// sensors' drift.
#include <limits>

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

  explicit EkfFilter(const FusionConfig& cfg = {});
  LocalizationState state() const override;
  std::string_view name() const override { return "ekf"; }

 private:
  void advance(Stamp t) override { predict(t); }
  void predict(Stamp t);
  // The measurement z of prediction h; returns its normalised innovation squared (NIS), and applies it only when
  // that is at most `gate`. `consider`: a state this update must not move.
  template <int M>
  double update(const Eigen::Matrix<double, M, 1>& z, const Eigen::Matrix<double, M, 1>& h,
                const Eigen::Matrix<double, M, kN>& H, const Eigen::Matrix<double, M, M>& Rm, int consider = -1,
                double gate = std::numeric_limits<double>::infinity());
  void on_imu(const ImuSample& s) override;
  void on_speed(const BodySpeed& s) override;
  void on_gnss(const GnssFix& f) override;
  void on_gnss_velocity(const GnssFix& f);
  void on_odometry(const OdometryIncrement& o) override;
  void on_map_pose(const MapPose& m) override;
  void apply_heading(const HeadingInitialiser::Offset& off, double fix_sigma);

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
