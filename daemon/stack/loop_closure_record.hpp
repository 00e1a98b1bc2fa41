#pragma once
// What the Stack reports of each loop closure (lidar_odometry): the scorecard's odometry.loop_closures.
#include "common/geometry.hpp"
#include "common/time.hpp"

namespace fsd {

// A loop closed (lidar_odometry): what the LoopCloser found and what the Stack moved.
struct LoopClosureRecord {
  Stamp t = 0;           // the newest keyframe's instant
  int lap = 0;           // 1 for the first loop
  Pose2 estimate;        // the pose there before the correction
  Pose2 correction;      // map ← estimated
  int pairs = 0;         // start cones seen again
  double rms = 0;        // m over those pairs
  int keyframes = 0;     // of the solved lap
  int cones_merged = 0;  // mapped twice, one cone again after the correction
  double solve_s = 0;    // wall time of the lap's pose-graph solve, wherever it ran (a worker in real time), s
  double control_s = 0;  // the control thread's wall time of the closing (the alignment, the solve when it ran
                         // there, the correction applied), s
};

}  // namespace fsd
