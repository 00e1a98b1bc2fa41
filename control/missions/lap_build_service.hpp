#pragma once
// Where lap 2's path is built (RecordedTrajectory::build, 10–30 ms, once per run: bench/control_bench
// BM_LapBuild). The autopilot hands the job over and polls for its result each step; the daemon's Stack owns the
// worker that runs it (a thread of its own on the car and in real-time runs, the caller's own thread in headless
// runs and replay). Without a service the autopilot builds the lap inside the step that asks for it.
#include "common/job_service.hpp"
#include "control/planning/recorded_trajectory.hpp"

namespace fsd {

using LapBuildService = JobService<TrajectoryResult>;
using LapBuildJob = LapBuildService::Job;  // with copies of its inputs (lap 1's poses, the map)

}  // namespace fsd
