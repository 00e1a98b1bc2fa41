#pragma once
// The expensive half of a loop closure (issue #17): the lap's pose graph solved with the start's cones tied, 110–410
// ms of Ceres for 200–300 keyframes. The LoopCloser hands it out as a LoopSolve holding copies of all it needs, so
// that any thread can run solve_loop() while frames keep coming; the closer takes the result back (finish).
//
// A pure core: no clock, no I/O, no thread.
#include <vector>

#include "common/types.hpp"
#include "localization/loop_closure/lap_graph.hpp"

namespace fsd::loop_closure {

// One keyframe of a closed lap: where the estimator had the car, and where the solved graph puts it.
struct ClosedKeyframe {
  Stamp t = 0;
  Pose2 estimate, optimised;
};

struct LoopClosure {
  Stamp t = 0;                            // the newest keyframe's instant
  int lap = 0;                            // 1 for the first loop closed
  Pose2 correction;                       // map ← estimated, at the newest keyframe
  int pairs = 0;                          // cones of the start's scene seen again
  double rms = 0;                         // m over those pairs after the alignment
  std::vector<ClosedKeyframe> keyframes;  // the lap's, in time order

  // map ← estimated for a pose estimated at `t`: identity before the lap's first keyframe (already in the map
  // frame), the newest keyframe's after the last, interpolated between keyframes.
  Pose2 correction_at(Stamp t) const;
};

// A lap's loop to solve: its graph with the start's cones tied, and what the closure reports.
struct LoopSolve {
  LapGraph graph;
  std::vector<Stamp> stamps;     // the lap's keyframes, in time order ...
  std::vector<Pose2> estimates;  // ... and the estimator's poses there
  std::vector<Cone> reference;   // the start's scene as this lap's landmarks (id: the landmark's)
  int pairs = 0;
  double rms = 0;
};

struct LoopSolveResult {
  bool solved = false;
  LoopClosure closure;            // lap 0: the closer numbers the laps it takes
  std::vector<Cone> start_scene;  // the reference cones where the solve put them (map frame)
};

LoopSolveResult solve_loop(const LoopSolve& s);

}  // namespace fsd::loop_closure
