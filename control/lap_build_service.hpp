#pragma once
// Where lap 2's path is built (RecordedTrajectory::build, 10–30 ms, once per run: bench/control_bench
// BM_LapBuild). The autopilot hands the job over and polls for its result each step; the daemon's Stack owns the
// worker that runs it (a thread of its own on the car and in real-time runs, the caller's own thread in headless
// runs and replay). Without a service the autopilot builds the lap inside the step that asks for it.
#include <functional>
#include <optional>

#include "control/recorded_trajectory.hpp"

namespace fsd {

// A build with copies of its inputs (lap 1's poses, the map), safe to run on any thread.
using LapBuildJob = std::function<TrajectoryResult()>;

class LapBuildService {
 public:
  virtual ~LapBuildService() = default;
  // Takes the job to build elsewhere; false when it cannot (the caller then builds it itself). One job at a time.
  virtual bool submit(LapBuildJob job) = 0;
  // The result of the submitted job, once, when it is ready; nullopt while it is still being built.
  virtual std::optional<TrajectoryResult> poll() = 0;
};

}  // namespace fsd
