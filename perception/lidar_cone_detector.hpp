#pragma once
// The LiDAR stages chained (DESIGN.md §3 perception, paper §III.A): one VLP-16 scan in, cone detections out.
//
//   Scan (sensor frame) ─► deskew into the body frame at the scan's last firing (ScanMotion)
//   ─► ROI box, body cut out (RoiFilter) ─► ground plane (GroundFitter) ─► split: ground / obstacles ≤ max_height
//   ─► accumulate the last m frames' obstacles (FrameAccumulator) ─► clusters (Clusterer)
//   ─► size filter and position (ConeSizeFilter; too wide: split into touching cones, TouchingConesSplitter) ─► colour from reflectivity (IntensityColourClassifier)
//   ─► ConeDetections + the candidates for the camera stage.
//
// Pure: no I/O, no clock, no thread; one owner. Body poses come from the caller as a function of time (truth,
// odometry or the fused estimate); without them the scan is taken as it is and nothing is accumulated.
#include <cstdint>
#include <vector>

#include "common/config.hpp"
#include "common/types.hpp"
#include "perception/candidate.hpp"
#include "perception/clusterer.hpp"
#include "perception/cone_quality.hpp"
#include "perception/cone_size_filter.hpp"
#include "perception/frame_accumulator.hpp"
#include "perception/ground_fitter.hpp"
#include "perception/ground_split.hpp"
#include "perception/intensity_colour.hpp"
#include "perception/roi_filter.hpp"
#include "perception/scan_motion.hpp"
#include "perception/touching_cones.hpp"

namespace fsd {

struct LidarDetectorConfig {
  RoiConfig roi;
  GroundConfig ground;
  AccumulationConfig accumulation;
  ClusterConfig cluster;
  ConeSizeConfig size;
  TouchingConesConfig touching;
  IntensityColourConfig colour;
  ConeQualityConfig quality;
};
// The sections under "perception.lidar.*".
void describe_lidar_detector_config(ConfigSchema& schema);
LidarDetectorConfig read_lidar_detector_config(const Config& cfg);

// What each stage kept and dropped in one frame (for /metrics: sum them over frames).
struct LidarStageCounters {
  std::uint64_t input = 0;                 // points of the scan
  std::uint64_t invalid = 0;               // non-finite coordinates
  std::uint64_t outside_roi = 0;           // outside the box
  std::uint64_t in_body = 0;               // on the car itself
  std::uint64_t ground = 0;                // ground plane inliers (removed)
  std::uint64_t below_ground = 0;          // more than τ below the plane (dropped)
  std::uint64_t above_roi = 0;             // higher than the region above the ground (dropped)
  std::uint64_t obstacles = 0;             // this frame's points kept for clustering
  std::uint64_t grazing = 0;               // of them, found along grazing beams within the ground band
  std::uint64_t accumulation_dropped = 0;  // over the per-frame bound
  std::uint64_t clustered = 0;             // points clustered (all accumulated frames)
  std::uint64_t clusters = 0;              // clusters within the point bounds
  std::uint64_t clusters_too_large = 0;
  std::uint64_t too_sparse = 0, too_wide = 0, too_tall = 0, not_cone_shaped = 0, too_flat = 0, floating = 0;
  std::uint64_t beside_taller = 0;
  std::uint64_t split_clusters = 0;  // too wide for one cone, split into touching cones (each a cone by itself)
  std::uint64_t split_cones = 0;     // the cones they were split into
  std::uint64_t black = 0;           // black rubber by its reflectivity (tyres, tyre stacks)
  std::uint64_t cones = 0;
  std::uint64_t coloured = 0;            // cones with a colour from the reflectivity
  std::uint64_t local_ground_cells = 0;  // grid cells whose ground was corrected from the plane
  bool ground_fallback = false;          // no plane found: the previous (or nominal) plane was used
};

// A cluster the size filter rejected, for the dashboard and diagnostics.
struct RejectedCluster {
  Vec3 position = Vec3::Zero();  // where its base centre would be
  double width = 0, height = 0, bottom = 0;
  std::uint32_t points = 0;
  ConeRejection reason = ConeRejection::None;
};

struct LidarDetection {
  ConeDetections detections;              // vehicle frame at detections.stamp, the scan's last firing
  std::vector<ConeCandidate> candidates;  // candidates[i] is detections.cones[i]
  GroundPlane ground;                     // in the vehicle frame at that time (local corrections not included)
  std::vector<Point> ground_points;       // this scan's ground points (vehicle frame, deskewed)
  std::vector<Point> obstacle_points;     // the clustered cloud: this scan's and the accumulated obstacle points
  std::vector<RejectedCluster> rejected;  // clusters within the point bounds that are not cones
  int frames = 1;                         // frames in the clustered cloud
  std::vector<Cone> camera_rejected;      // candidates the camera stage judged not to be cones (lidar_camera_detector)
  LidarStageCounters counters;
};

class LidarConeDetector {
 public:
  // `body_from_sensor`: the LiDAR mount (body ← sensor), e.g. Vlp16Config::body_from_sensor(). Throws
  // std::invalid_argument for an unknown method name.
  LidarConeDetector(const LidarDetectorConfig& cfg, const Pose3& body_from_sensor);

  // One scan. `pose_at`: odometry/map ← body at any time of the scan (deskew and accumulation); empty = no motion
  // known: the scan is used as it is and not accumulated.
  LidarDetection detect(const Scan& scan, const BodyPoseAt& pose_at = {});
  // Forgets the accumulated frames and the last ground plane (after a relocalisation or a gap in the stream).
  void reset();

  const LidarDetectorConfig& config() const { return cfg_; }

 private:
  LidarDetectorConfig cfg_;
  Pose3 body_from_sensor_;
  RoiFilter roi_;
  GroundFitter ground_;
  GroundSplitter splitter_;
  FrameAccumulator accumulator_;
  Clusterer clusterer_;
  ConeSizeFilter size_;
  TouchingConesSplitter touching_;
  LidarShadow shadow_;
  IntensityColourClassifier colour_;
  GroundPlane last_ground_;
  std::vector<Point> cropped_, obstacles_;  // reused between frames
};

}  // namespace fsd
