#pragma once
// Lap 1's real-time plans on a thread of their own (Autopilot::set_plan_service), so that the control thread keeps
// its period: a plan takes a few milliseconds, ten times a second. Each job's CPU time is kept for the Stack's
// planning figures (the control thread only hands the job over). The destructor waits for a plan under way.
#include <atomic>
#include <chrono>
#include <functional>

#include "common/thread_cpu.hpp"
#include "control/planning/plan_service.hpp"
#include "daemon/stack/job_thread.hpp"

namespace fsd {

class PlanThread final : public PlanService {
 public:
  PlanThread() : worker_([](const std::exception& e) { return failed(e); }) {}

  bool submit(Job job) override {
    const bool taken = worker_.submit([this, job = std::move(job)] {
      const double c0 = thread_cpu_seconds();
      PlanResult r = job();
      cpu_s_.store(thread_cpu_seconds() - c0);
      return r;
    });
    if (taken && run_clock_) {
      submitted_run_ = run_clock_();
      out_ = true;
    }
    return taken;
  }
  std::optional<PlanResult> poll() override {
    if (!run_clock_) return worker_.poll();
    if (!out_ || run_clock_() - submitted_run_ < latency_s_) return std::nullopt;
    while (!worker_.ready_at(JobThread<PlanResult>::Clock::now() + std::chrono::seconds(1))) {
    }  // waits for the plan (bounded: a plan takes milliseconds)
    out_ = false;
    return worker_.poll();
  }
  // A run faster than real time: each plan taken `latency_s` of run time after it was handed over (the planner's
  // budget), waiting for it if need be. Unlike the once-a-lap jobs' pacing by the wall time a job took, this keeps
  // such a run the same every time: a plan's few milliseconds vary with the machine's load, and so would the run.
  void pace_by(std::function<double()> run_clock, double latency_s) {
    run_clock_ = std::move(run_clock);
    latency_s_ = latency_s;
  }
  // CPU seconds of the newest plan taken.
  double last_cpu_s() const { return cpu_s_.load(); }

 private:
  static PlanResult failed(const std::exception& e) {
    PlanResult r;
    r.reason = std::string("planner failed: ") + e.what();
    return r;
  }

  std::atomic<double> cpu_s_{0.0};
  std::function<double()> run_clock_;
  double latency_s_ = 0.0, submitted_run_ = 0.0;
  bool out_ = false;
  JobThread<PlanResult> worker_;  // last: its thread starts with it
};

}  // namespace fsd
