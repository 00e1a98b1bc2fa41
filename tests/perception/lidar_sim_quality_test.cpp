// The LiDAR stages on scans the virtual car's VLP-16 renders along the shared trackdrives (distractors on),
// decoded by the real VLP-16 decoder, scored against the world's true cones (recall, precision, position RMSE,
// intensity colour) with the scorecard's pairing.
#include <gtest/gtest.h>

#include <cstdio>

#include "perception/lidar_cone_detector.hpp"
#include "tests/perception/lidar_eval.hpp"
#include "tests/perception/sim_lidar_drive.hpp"

namespace fsd {
namespace {

using test::LidarEval;
using test::SimLidarDrive;
using test::SimLidarSetup;

LidarEval run(const SimLidarSetup& setup, int frames, const LidarDetectorConfig& cfg = {}) {
  SimLidarDrive drive(setup);
  LidarConeDetector det(cfg, drive.mount());
  LidarEval eval;
  const auto truth = drive.true_cones();
  const BodyPoseAt pose_at = [&](Stamp t) { return drive.body_pose(t); };
  for (int i = 0; i < frames; ++i) {
    const Scan scan = drive.next();
    const LidarDetection d = det.detect(scan, pose_at);
    eval.add(d.detections, truth, drive.body_pose(d.detections.stamp));
  }
  return eval;
}

TEST(LidarSimQuality, Explore) {
  for (const char* t : {"epfl_track_1", "epfl_track_2", "epfl_track_3", "amz_fssim_thin"}) {
    SimLidarSetup s;
    s.track = std::string("../shared/tracks/") + t + ".csv";
    const LidarEval e = run(s, 60);
    std::printf("%s: %s\n", t, e.summary().c_str());
  }
}

}  // namespace
}  // namespace fsd
