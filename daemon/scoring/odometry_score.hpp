#pragma once
// The scorecard's "odometry" section (DESIGN.md §8): how far the estimated poses are from the simulator's true
// ones. Two tracks of (true, estimated) pose pairs:
// - the localization source's state each cycle (whatever drives the car): ATE, the RMS and worst planar distance,
//   and the RMS and worst heading error (a heading off by 0.5° puts a cone 10 m away 9 cm off in the map);
// - the LiDAR odometry's pose at each scan, when it runs: its drift per distance, at the end of the run (end-point
//   error over the path length) and KITTI-style (the mean relative planar error over every 50 m segment, per
//   distance: a closed lap cannot flatter it).
// Both are bounded: pairs are kept every `spacing` metres driven (a 10-lap run at 0.5 m: ~6 k pairs).
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "common/geometry.hpp"

namespace fsd {

struct PosePair {
  Pose2 truth, estimate;
};

// Drift of an estimated track against the true one (pairs in time order, from a common start).
struct Drift {
  double distance_m = 0;   // true path length
  double end_error_m = 0;  // planar distance between the last estimated and true positions
  double end_pct = 0;      // end_error_m / distance_m, %
  double segment_pct = 0;  // KITTI-style over `segment` m, %; 0 when the track is shorter than one segment
  int segments = 0;
};
Drift drift_of(const std::vector<PosePair>& track, double segment = 50.0);

class OdometryScore {
 public:
  explicit OdometryScore(double spacing = 0.5) : spacing_(spacing) {}
  // The localization source's state against the truth at the same instant.
  void add_state(const Pose2& truth, const Pose2& estimate);
  // The LiDAR odometry's pose at a scan against the truth at the scan's instant.
  void add_lidar(const Pose2& truth, const Pose2& estimate);
  // {"source", "ate_m", "ate_max_m", "yaw_rms_deg", "yaw_max_deg", "samples"} and, when the LiDAR odometry ran,
  // "lidar": {"distance_m", "end_error_m", "drift_pct" (end-point), "segment_drift_pct" (50 m), "scans"};
  // "drift_pct" at the top is the LiDAR odometry's end-point drift (absent without it).
  nlohmann::json to_json(const std::string& source) const;

 private:
  static void keep(std::vector<PosePair>& track, const PosePair& p, double spacing);
  double spacing_;
  double sum_sq_ = 0, max_ = 0;          // planar distance
  double yaw_sum_sq_ = 0, yaw_max_ = 0;  // heading error (rad)
  long samples_ = 0, scans_ = 0;
  std::vector<PosePair> lidar_;
};

}  // namespace fsd
