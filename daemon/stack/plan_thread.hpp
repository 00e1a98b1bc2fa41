#pragma once
// Lap 1's real-time plans on a thread of their own (Autopilot::set_plan_service), so that the control thread keeps
// its period: a plan takes a few milliseconds, ten times a second. Each job's CPU time is kept for the Stack's
// planning figures (the control thread only hands the job over). The destructor waits for a plan under way.
#include <atomic>
#include <functional>

#include "common/thread_cpu.hpp"
#include "control/planning/plan_service.hpp"
#include "daemon/stack/job_thread.hpp"

namespace fsd {

class PlanThread final : public PlanService {
 public:
  PlanThread() : worker_([](const std::exception& e) { return failed(e); }) {}

  bool submit(Job job) override {
    return worker_.submit([this, job = std::move(job)] {
      const double c0 = thread_cpu_seconds();
      PlanResult r = job();
      cpu_s_.store(thread_cpu_seconds() - c0);
      return r;
    });
  }
  std::optional<PlanResult> poll() override { return worker_.poll(); }
  // A run faster than real time: each plan taken `latency_s` of run time after it was handed over (the planner's
  // budget), waiting for it if need be. Unlike the once-a-lap jobs' pacing by the wall time a job took, this keeps
  // such a run the same every time: a plan's few milliseconds vary with the machine's load, and so would the run.
  void pace_by(std::function<double()> run_clock, double latency_s) {
    worker_.pace_by(std::move(run_clock), latency_s);
  }
  std::optional<std::string> set_realtime(int priority) { return worker_.set_realtime(priority); }
  // CPU seconds of the newest plan taken.
  double last_cpu_s() const { return cpu_s_.load(); }

 private:
  static PlanResult failed(const std::exception& e) {
    PlanResult r;
    r.reason = std::string("planner failed: ") + e.what();
    return r;
  }

  std::atomic<double> cpu_s_{0.0};
  FixedLatencyJobThread<PlanResult> worker_;  // last: its thread starts with it
};

}  // namespace fsd
