#pragma once
// run.localization_source = fused: the Stack's GNSS-INS samples and the VCU's wheel speeds through one fusion
// filter (localization/fusion, localization.fusion.filter). A GNSS sample gives a position fix (rear axle, lever
// arm removed by the driver) with its quality, age and dual-antenna heading, and its yaw rate (ROT) stands for
// the gyro; the mean of the rear wheels is the rear axle's forward speed; with localization.fusion.lidar_odometry
// the LiDAR odometry's increments too (the paper's LiDAR odometry ⊕ GNSS-INS). Measurements go in by stamp.
//
// Without satellites (run.localization_source = lidar_odometry, `Satellites::Denied`) the same filter runs on the
// GNSS-INS unit's gyro alone of what it sends (no fix, no receiver heading, no velocity over ground), the wheels
// and the LiDAR odometry's increments, started at localization.start (which then defines the map frame) and held
// to the cone map by its matches and the loop closures: one filter for every source.
#include <memory>
#include <optional>
#include <vector>

#include "common/config.hpp"
#include "common/types.hpp"
#include "localization/fusion/fusion_filter.hpp"

namespace fsd {

class FusedLocalization {
 public:
  enum class Satellites { Used, Denied };
  explicit FusedLocalization(const Config& cfg, Satellites satellites = Satellites::Used);
  // One cycle's input: the GNSS samples since the last cycle and the newest VCU status (if any).
  // `odometry`: the LiDAR odometry's newest increment, when it took a scan this cycle.
  void add(const std::vector<GnssSample>& gnss, const std::optional<VcuStatus>& vcu,
           const std::optional<fusion::OdometryIncrement>& odometry = std::nullopt);
  bool takes_lidar_odometry() const { return lidar_odometry_; }
  // Whether a GNSS fix was accepted within localization.fusion.good_gnss_timeout_s of the filter's time.
  bool gnss_recent() const;
  // The cone map's word on the pose while the GNSS is not recent: `correction` (map ← estimated, a frame's whole
  // alignment from localization/map_match) laid onto the filter's pose now, a MapPose measurement of that σ.
  // What the filter moved its pose by (map ← before) when it took it; nothing when it gated it away.
  std::optional<Pose2> add_map_correction(const Pose2& correction, double sigma, double yaw_sigma);
  // A loop closure's correction of the map frame (map ← estimated) onto the filter's pose.
  void relocate(const Pose2& map_from_estimate) { filter_->relocate(map_from_estimate); }
  bool satellites_denied() const { return satellites_ == Satellites::Denied; }
  // The vehicle state once the filter has a position and a heading.
  std::optional<VehicleState> state(double steering_measured) const;
  fusion::LocalizationState estimate() const { return filter_->state(); }

 private:
  std::unique_ptr<fusion::FusionFilter> filter_;
  Satellites satellites_ = Satellites::Used;
  Stamp last_vcu_ = -1e300;
  bool lidar_odometry_ = false;
  double good_gnss_timeout_ = 1.0;
  double wheelbase_ = 0;  // m: the wheels' kinematic yaw rate
};

}  // namespace fsd
