#pragma once
// Where a lap's loop closure is solved (loop_closure::solve_loop: the lap's pose graph, 110–410 ms of Ceres once a
// lap). The Stack hands the job over and polls for its result each step; meanwhile frames keep coming and the
// LoopCloser holds them. On the car and in real-time runs a thread of the Stack's runs it (LoopSolveThread);
// without a service (headless runs and replay, which must stay deterministic) the Stack solves inside the step.
#include "common/job_service.hpp"
#include "localization/loop_closure/loop_solve.hpp"

namespace fsd {

struct SolvedLoop {
  loop_closure::LoopSolveResult result;
  double solve_s = 0;  // wall time of the solve where it ran, s
};

using LoopSolveService = JobService<SolvedLoop>;
using LoopSolveJob = LoopSolveService::Job;  // with copies of its inputs (the lap's graph)

}  // namespace fsd
