#pragma once
// Where lap 1's real-time plans are made (RealtimePlanner::plan, a few ms: bench/control_bench BM_RealtimePlan).
// The autopilot hands each plan over with copies of its inputs and takes the newest result as it comes, so that the
// control cycle keeps its period; the daemon's Stack owns the worker (daemon/stack/plan_thread.hpp) on the car and in
// real-time runs. Without a service the autopilot plans inside the cycle, as headless runs and replay do to stay
// repeatable.
#include "common/job_service.hpp"
#include "control/planning/realtime_planner.hpp"

namespace fsd {

using PlanService = JobService<PlanResult>;
using PlanJob = PlanService::Job;

}  // namespace fsd
