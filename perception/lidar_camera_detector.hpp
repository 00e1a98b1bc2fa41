#pragma once
// The paper's detection system end to end (DESIGN.md §5b, paper §III): the LiDAR stages find cone candidates in
// one scan, the camera stage verifies and colours those it can see in the camera frame taken nearest the scan.
// What the daemon's run.perception_source = lidar (no camera stage) and lidar_camera run.
//
// The candidates are in the vehicle frame at the scan's last firing; the camera frame was taken at another
// instant (20 Hz against 10 Hz, plus its latency), so each candidate is moved into the vehicle frame at the
// frame's capture time by the body poses before it is projected, and its verdict is carried back.
// A camera verdict replaces the LiDAR's reflectivity colour, except that a camera that cannot name the colour
// ("unknown") leaves the reflectivity's. Candidates the camera cannot judge (outside the image, too far, no
// recent frame, a frame that does not decode) stay as the LiDAR found them: unverified.
//
// Pure: no I/O, no clock, no thread.
#include <cstdint>
#include <memory>
#include <optional>

#include <opencv2/core/mat.hpp>

#include "perception/camera/camera_stage.hpp"
#include "perception/lidar_cone_detector.hpp"

namespace fsd {

// One decoded camera frame and when it was taken (the run's clock).
struct CameraImage {
  Stamp capture = 0;
  cv::Mat bgr;  // CV_8UC3
};

struct LidarCameraCounters {
  std::uint64_t scans = 0;
  std::uint64_t camera_frames_used = 0;
  std::uint64_t no_recent_frame = 0;  // scans with no camera frame within max_camera_gap
  CameraStageStats camera;            // the camera stage's own
};

// The camera stage on one LiDAR detection: each cone moved from the vehicle frame at det.detections.stamp to the
// one at image.capture by `pose_at` (none: the car stood still), verified, its verdict carried back to the cone as
// the LiDAR placed it; rejected cones leave the detections and their candidates for det.camera_rejected.
// `beam_spacing_rad`: the LiDAR's angle between adjacent lasers. A cluster's top is where its highest laser hit, so
// the cone's tip can stand up to one laser gap higher: its height tells a big orange cone from a small one only when
// that gap cannot change the verdict; else the image decides (0: the height is taken as exact).
void verify_with_camera(CameraStage& camera, LidarDetection& det, const BodyPoseAt& pose_at, const CameraImage& image,
                        double beam_spacing_rad = 0.0);

class LidarCameraDetector {
 public:
  // Without a camera stage only the LiDAR stages run. `max_camera_gap`: s between the scan and the frame beyond
  // which the frame is not used.
  LidarCameraDetector(const LidarDetectorConfig& lidar, const Pose3& body_from_lidar,
                      std::unique_ptr<CameraStage> camera = nullptr, double max_camera_gap = 0.08);

  // One scan; `pose_at` as for LidarConeDetector::detect; `image` the camera frame nearest the scan (or none).
  LidarDetection detect(const Scan& scan, const BodyPoseAt& pose_at, const CameraImage* image);

  bool has_camera() const { return camera_ != nullptr; }
  const LidarCameraCounters& counters() const { return counters_; }
  void reset() { lidar_.reset(); }

 private:
  LidarConeDetector lidar_;
  std::unique_ptr<CameraStage> camera_;
  double max_camera_gap_;
  LidarCameraCounters counters_;
};

}  // namespace fsd
