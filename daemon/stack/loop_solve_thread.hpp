#pragma once
// The loop closure's solve on a thread of its own (StackOptions::loop_closure_worker), so that the control thread
// keeps its period when the lap's loop closes: the solve takes 110–410 ms, once a lap. The destructor waits for a
// solve under way.
#include "daemon/stack/job_thread.hpp"
#include "daemon/stack/loop_solve_service.hpp"

namespace fsd {

class LoopSolveThread final : public JobServiceThread<SolvedLoop> {
 public:
  LoopSolveThread() : JobServiceThread([](const std::exception&) { return SolvedLoop{}; }) {}  // unsolved: tried again
};

}  // namespace fsd
