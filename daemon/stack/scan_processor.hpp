#pragma once
// One LiDAR scan's heavy stages, for the Stack's processing thread (DESIGN.md §4: one thread for LiDAR frames, so
// that the control thread keeps its period): the LiDAR odometry's scan match and the perception stages (the LiDAR
// stages, and the camera stage on the camera frame nearest the scan). The processor owns those stages' state (the
// odometry's local map, the detector's accumulated frames); the Stack hands it everything else a scan needs as
// copies (ScanJob), so that the control thread and the processing thread share nothing while a scan is out. What
// is cheap and used every cycle stays on the control thread: the poses, the fusion filter, the cone map.
//
// The two stages share nothing, so they run side by side: perception on the calling thread, the scan match on a
// thread of the processor's own, joined before the result is returned. A scan's detections are then ready after
// the slower of the two stages rather than after both (the end-to-end latency), and the results do not depend on
// the timing (a replay gives the same commands).
//
// One scan at a time, in time order. No I/O, no clock but the wall clock it is given (the stages' figures).
#include <cstdint>
#include <exception>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "common/types.hpp"
#include "daemon/stack/job_thread.hpp"
#include "localization/lidar_odometry/lidar_odometry.hpp"
#include "localization/pose_history.hpp"
#include "perception/lidar_camera_detector.hpp"

namespace fsd {

struct ScanJob {
  std::shared_ptr<const Scan> scan;
  // The LiDAR odometry takes the scan, with the car's measured twist over it (none: its own prediction).
  bool odometry = false;
  std::optional<lidar_odometry::Vec6> measured;
  // Perception takes the scan, deskewed and accumulated by `poses` (the localization's, copied at hand-over).
  bool detect = false;
  PoseHistory poses;
  // The camera frame taken nearest the scan, as the camera sent it (decoded here).
  std::shared_ptr<const std::vector<std::uint8_t>> camera_jpeg;
  Stamp camera_capture = 0;
};

struct ScanResult {
  std::shared_ptr<const Scan> scan;
  std::optional<lidar_odometry::OdometryOutput> odometry;
  std::optional<LidarDetection> detection;
  bool camera_decode_failed = false;  // a camera frame was given and did not decode (the LiDAR stages alone ran)
  std::optional<LidarCameraCounters> detector_counters;  // the detector's, after this scan
  double odometry_s = 0, perception_s = 0;               // wall time of each
  std::string failure;                                   // the processing threw: what (nothing else is set)

  static ScanResult failed(const std::exception& e) {
    ScanResult r;
    r.failure = e.what();
    return r;
  }
};

class ScanProcessor {
 public:
  // Either stage may be absent (a source that does not use it). `wall`: seconds, for the stages' figures only.
  ScanProcessor(std::unique_ptr<LidarCameraDetector> detector, std::unique_ptr<lidar_odometry::LidarOdometry> odometry,
                std::function<double()> wall);
  ~ScanProcessor();

  // Both stages' results; a stage that throws fails the scan (ScanResult::failure), the other's result dropped.
  ScanResult process(ScanJob job);

  // The odometry's thread under SCHED_FIFO at `priority` (the caller's thread is the caller's to set); what
  // failed, or nothing.
  std::optional<std::string> set_realtime(int priority);

 private:
  struct OdometryRun {
    std::optional<lidar_odometry::OdometryOutput> output;
    double seconds = 0;
    std::string failure;
  };
  OdometryRun run_odometry(const Scan& scan, const std::optional<lidar_odometry::Vec6>& measured);
  void detect(const ScanJob& job, ScanResult& r);

  std::unique_ptr<LidarCameraDetector> detector_;
  std::unique_ptr<lidar_odometry::LidarOdometry> odometry_;
  std::function<double()> wall_;
  std::unique_ptr<JobThread<OdometryRun>> odometry_thread_;  // with both stages only; last: joined first
};

}  // namespace fsd
