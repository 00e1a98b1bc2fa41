#pragma once
// One interface for the fusion filters (issue #17): measurements in, in time order, and the state out. The filters
// are pure: no clock, no I/O; time is the measurements' stamps. Chosen by name with make_fusion_filter (config key
// localization.fusion.filter).
#include <memory>
#include <string>
#include <string_view>

#include "localization/fusion/fusion_config.hpp"
#include "localization/fusion/measurements.hpp"

namespace fsd::fusion {

class FusionFilter {
 public:
  virtual ~FusionFilter() = default;
  // Measurements in time order across all kinds; one older than the filter's time (beyond a millisecond) is
  // counted and dropped, a stale GNSS fix is rejected by the gate. The filter is brought to the measurement's
  // time (advance), then the measurement applied by its kind.
  void add(const Measurement& m);
  // The pose is known before any measurement, to σ per horizontal axis and `yaw_sigma`: the car staged at the start
  // of a run without satellites, whose pose there defines the map frame. The filter is initialised at once.
  virtual void start_at(const Pose2& pose, double sigma, double yaw_sigma) = 0;
  // The map frame was corrected (a loop closure): the pose moves by `map_from_estimate` (map ← the pose as state()
  // gave it); the body velocities, the rates and what the filter learnt stay.
  virtual void relocate(const Pose2& map_from_estimate) = 0;
  virtual LocalizationState state() const = 0;
  virtual std::string_view name() const = 0;
  std::uint64_t dropped_out_of_order() const { return dropped_; }

 protected:
  virtual void advance(Stamp t) = 0;  // predict / integrate to t (sets t_)
  virtual void on_imu(const ImuSample& s) = 0;
  virtual void on_speed(const BodySpeed& s) = 0;
  virtual void on_gnss(const GnssFix& f) = 0;
  virtual void on_odometry(const OdometryIncrement& o) = 0;
  virtual void on_map_pose(const MapPose& m) = 0;

  Stamp t_ = 0;  // the filter's time

 private:
  bool started_ = false;
  std::uint64_t dropped_ = 0;
};

// "ekf" | "complementary"; throws std::invalid_argument for another name.
std::unique_ptr<FusionFilter> make_fusion_filter(const std::string& name, const FusionConfig& cfg = {});

// The quality flag of a state from its covariance, its GNSS history and its inputs' freshness.
Quality assess_quality(const LocalizationState& s, Stamp last_motion, const FusionCommonConfig& cfg);

}  // namespace fsd::fusion
