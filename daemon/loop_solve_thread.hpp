#pragma once
// The loop closure's solve on a thread of its own (StackOptions::loop_closure_worker), so that the control thread
// keeps its period when the lap's loop closes: the solve takes 110–410 ms, once a lap. The destructor waits for a
// solve under way.
#include "daemon/job_thread.hpp"
#include "daemon/loop_solve_service.hpp"

namespace fsd {

class LoopSolveThread final : public LoopSolveService {
 public:
  LoopSolveThread() : worker_([](const std::exception&) { return SolvedLoop{}; }) {}  // unsolved: tried again

  bool submit(LoopSolveJob job) override { return worker_.submit(std::move(job)); }  // false while a job is out
  std::optional<SolvedLoop> poll() override { return worker_.poll(); }

 private:
  JobThread<SolvedLoop> worker_;
};

}  // namespace fsd
