#pragma once
// Lap 1's real-time plans on a thread of their own (Autopilot::set_plan_service), so that the control thread keeps
// its period: a plan takes a few milliseconds, ten times a second. Each job's CPU time is kept for the Stack's
// planning figures (the control thread only hands the job over). The destructor waits for a plan under way.
#include <atomic>
#include <ctime>

#include "control/planning/plan_service.hpp"
#include "daemon/job_thread.hpp"

namespace fsd {

class PlanThread final : public PlanService {
 public:
  PlanThread() : worker_([](const std::exception& e) { return failed(e); }) {}

  bool submit(Job job) override {
    return worker_.submit([this, job = std::move(job)] {
      const double c0 = thread_cpu();
      PlanResult r = job();
      cpu_s_.store(thread_cpu() - c0);
      return r;
    });
  }
  std::optional<PlanResult> poll() override { return worker_.poll(); }
  // A run faster than real time: results taken once as much run time has passed as the plan took.
  void pace_by(std::function<double()> run_clock) { worker_.pace_by(std::move(run_clock)); }
  // CPU seconds of the newest plan taken.
  double last_cpu_s() const { return cpu_s_.load(); }

 private:
  static PlanResult failed(const std::exception& e) {
    PlanResult r;
    r.reason = std::string("planner failed: ") + e.what();
    return r;
  }
  static double thread_cpu() {
    timespec ts{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
  }

  std::atomic<double> cpu_s_{0.0};
  JobServiceThread<PlanResult> worker_;  // last: its thread starts with it
};

}  // namespace fsd
