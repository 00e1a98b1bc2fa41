#pragma once
// LOAM-style LiDAR odometry (DESIGN.md §3 localization): per scan, features (features.hpp) deskewed with the
// constant-velocity motion of the previous increment, registered against the previous scan and a local map of a
// few keyframes (registration.hpp). Output: the body increment the fusion filters take, the accumulated pose, and
// diagnostics. A pure core: no clock, no I/O, no thread; the caller hands in scans in time order.
#include <deque>
#include <optional>
#include <vector>

#include "common/types.hpp"
#include "localization/fusion/measurements.hpp"
#include "localization/lidar_odometry/config.hpp"
#include "localization/lidar_odometry/features.hpp"
#include "localization/lidar_odometry/registration.hpp"

namespace fsd::lidar_odometry {

struct OdometryDiagnostics {
  int edges = 0, planes = 0;  // features of the scan
  int edge_matches = 0, plane_matches = 0;
  int iterations = 0;
  bool degenerate = false;
  int degenerate_directions = 0;
  double min_information = 0;  // smallest eigenvalue of the scaled normal matrix
  double rms = 0;              // m
};

struct OdometryOutput {
  bool has_increment = false;  // false for the first scan (nothing to compare with)
  fusion::OdometryIncrement increment;
  Pose3 pose = Pose3::Identity();              // odometry frame ← body at `stamp` (the origin given to start_at)
  Stamp stamp = 0;                             // the scan's last firing: the time the pose refers to
  Matrix6d covariance = Matrix6d::Identity();  // of the increment, body-frame (x, y, z, roll, pitch, yaw)
  OdometryDiagnostics diagnostics;
};

class LidarOdometry {
 public:
  LidarOdometry(const LidarOdometryConfig& cfg, const Pose3& body_from_sensor);
  // The body pose the first scan is taken at (identity by default).
  // `twist`: the body's velocity (v, ω) per second then, if the caller knows it (wheel speeds, the fusion): a start
  // at speed otherwise begins from a standing prediction, which at 12 m/s is too far off to match (measured).
  void start_at(const Pose3& origin, const Vec6& twist = Vec6::Zero()) {
    origin_ = origin;
    velocity_ = twist;
  }
  // `measured_twist`: the body's velocity (v, ω) over the scan as the car measured it (wheel speeds, gyro), when
  // the caller has it: the deskew and the prediction then use it instead of the low-passed increments, which lag
  // braking and turn-in by half a second and lose track under hard acceleration.
  OdometryOutput process(const Scan& scan, const std::optional<Vec6>& measured_twist = std::nullopt);
  bool started() const { return started_; }
  const Pose3& pose() const { return pose_; }

 private:
  std::vector<Vec3> deskew(const std::vector<FeaturePoint>& pts, Stamp t_ref) const;
  void add_to_map(const std::vector<Vec3>& edges, const std::vector<Vec3>& planes, bool keyframe);
  void rebuild_map();

  LidarOdometryConfig cfg_;
  Pose3 body_from_sensor_;
  FeatureExtractor extractor_;
  Registration registration_;
  Pose3 origin_ = Pose3::Identity();
  bool started_ = false;
  Pose3 pose_ = Pose3::Identity();
  Stamp stamp_ = 0;
  Vec6 velocity_ = Vec6::Zero();  // body twist (v, ω) per second
  struct Cloud {
    std::vector<Vec3> edges, planes;  // odometry frame
  };
  std::deque<Cloud> keyframes_;
  Cloud last_;  // the previous scan, whether a keyframe or not
  Pose3 last_keyframe_ = Pose3::Identity();
  FeatureMap map_;
};

}  // namespace fsd::lidar_odometry
