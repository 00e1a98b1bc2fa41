#pragma once
// One thread of its own that runs one job at a time for a caller that must not wait for it (the control thread):
// submit() hands a job over, poll() takes its result once. The thread is started with the object and joined by its
// destructor, which waits for a job under way to end (jobs cannot be interrupted midway; they are bounded).
// The workers of the Stack's slow, once-a-lap jobs (LapBuildThread, LoopSolveThread) are this.
#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <functional>
#include <mutex>
#include <optional>
#include <thread>
#include <utility>

#include "common/job_service.hpp"
#include "common/realtime.hpp"

namespace fsd {

template <class Result>
class JobThread {
 public:
  using Job = std::function<Result()>;
  // `failed` turns a job's exception into its result: a failed job is the caller's to report, not fatal here.
  explicit JobThread(std::function<Result(const std::exception&)> failed)
      : failed_(std::move(failed)), thread_([this] { run(); }) {}
  ~JobThread() {
    {
      std::lock_guard lock(m_);
      stop_ = true;
    }
    cv_.notify_all();
    thread_.join();
  }
  JobThread(const JobThread&) = delete;
  JobThread& operator=(const JobThread&) = delete;

  // False while a job is out (submitted, its result not yet polled): the caller then runs it itself or waits.
  bool submit(Job job) {
    {
      std::lock_guard lock(m_);
      if (busy_ || stop_) return false;
      busy_ = true;
      job_ = std::move(job);
      result_.reset();
    }
    cv_.notify_all();
    return true;
  }

  using Clock = std::chrono::steady_clock;

  // When the submitted job's result became ready, waiting for it at most until `deadline`; nullopt while it still
  // runs (or with nothing out).
  std::optional<Clock::time_point> ready_at(Clock::time_point deadline) {
    std::unique_lock lock(m_);
    cv_.wait_until(lock, deadline, [this] { return result_.has_value() || !busy_; });
    if (!result_) return std::nullopt;
    return ready_at_;
  }

  // The submitted job's result, once, waiting for it (the jobs are bounded); nullopt with nothing out.
  std::optional<Result> wait() {
    std::unique_lock lock(m_);
    cv_.wait(lock, [this] { return result_.has_value() || !busy_; });
    if (!result_) return std::nullopt;
    busy_ = false;
    return std::exchange(result_, std::nullopt);
  }

  // The submitted job's result, once, when it is ready; nullopt while it still runs (or with nothing out).
  std::optional<Result> poll() {
    std::lock_guard lock(m_);
    if (!result_) return std::nullopt;
    busy_ = false;
    return std::exchange(result_, std::nullopt);
  }

  // The thread under SCHED_FIFO at `priority` (common/realtime.hpp); what failed, or nothing.
  std::optional<std::string> set_realtime(int priority) { return fsd::set_realtime(priority, thread_.native_handle()); }

 private:
  void run() {
    std::unique_lock lock(m_);
    for (;;) {
      cv_.wait(lock, [this] { return stop_ || job_; });
      if (stop_) return;
      Job job = std::move(*job_);
      job_.reset();
      lock.unlock();
      std::optional<Result> r;
      try {
        r = job();
      } catch (const std::exception& e) {
        r = failed_(e);
      }
      lock.lock();
      result_ = std::move(r);
      ready_at_ = Clock::now();
      cv_.notify_all();
    }
  }

  std::function<Result(const std::exception&)> failed_;
  std::mutex m_;
  std::condition_variable cv_;
  std::optional<Job> job_;
  std::optional<Result> result_;
  Clock::time_point ready_at_;
  bool busy_ = false, stop_ = false;
  std::thread thread_;  // last: started once the members it uses are
};

// A JobThread for the jobs that come every few cycles (lap 1's plans, the scans' processing). Paced by a run clock
// (pace_by: a simulation faster than real time), a job's result is taken a fixed run time after its hand-over,
// waiting for it if need be: the run is then the same every time, as a job's milliseconds vary with the machine's
// load. Unpaced (real time), it is taken as soon as it is ready.
template <class Result>
class FixedLatencyJobThread {
 public:
  using Job = typename JobThread<Result>::Job;
  explicit FixedLatencyJobThread(std::function<Result(const std::exception&)> failed) : worker_(std::move(failed)) {}

  // False while a job is out.
  bool submit(Job job) {
    const bool taken = worker_.submit(std::move(job));
    if (taken && run_clock_) {
      submitted_run_ = run_clock_();
      out_ = true;
    }
    return taken;
  }
  std::optional<Result> poll() {
    if (!run_clock_) return worker_.poll();
    // (A nanosecond's tolerance: run clocks count cycles of a period that binary fractions do not hold exactly.)
    if (!out_ || run_clock_() - submitted_run_ < latency_s_ - 1e-9) return std::nullopt;
    out_ = false;
    return worker_.wait();  // due: waited for (bounded: the jobs take milliseconds)
  }
  std::optional<std::string> set_realtime(int priority) { return worker_.set_realtime(priority); }
  // Each result taken `latency_s` of run time (read on the calling thread) after its job was handed over.
  void pace_by(std::function<double()> run_clock, double latency_s) {
    run_clock_ = std::move(run_clock);
    latency_s_ = latency_s;
  }

 private:
  std::function<double()> run_clock_;
  double latency_s_ = 0.0, submitted_run_ = 0.0;
  bool out_ = false;
  JobThread<Result> worker_;  // last: its thread starts with it
};

// A JobService whose jobs run on a JobThread: LapBuildThread, LoopSolveThread.
//
// Paced by a run clock (pace_by: a simulation that runs faster than real time), a job's result is taken only once
// as much run time has passed since it was submitted as the job took on the wall clock, and poll() waits while the
// run clock is ahead of the job's wall time: the run drives on meanwhile for as long as the car would have, not for
// the many seconds a fast simulation covers in a solve's few hundred milliseconds.
template <class Result>
class JobServiceThread : public JobService<Result> {
 public:
  using Clock = typename JobThread<Result>::Clock;

  explicit JobServiceThread(std::function<Result(const std::exception&)> failed) : worker_(std::move(failed)) {}

  std::optional<std::string> set_realtime(int priority) { return worker_.set_realtime(priority); }
  // `run_clock`: the run's time in seconds (the Stack's step time), read on the calling thread.
  void pace_by(std::function<double()> run_clock) { run_clock_ = std::move(run_clock); }

  bool submit(typename JobService<Result>::Job job) override {
    if (!worker_.submit(std::move(job))) return false;
    if (run_clock_) submitted_ = {run_clock_(), Clock::now()};
    return true;
  }

  std::optional<Result> poll() override {
    if (!run_clock_) return worker_.poll();
    const auto run_elapsed = std::chrono::duration_cast<typename Clock::duration>(
        std::chrono::duration<double>(std::max(0.0, run_clock_() - submitted_.run)));
    const auto due = submitted_.wall + run_elapsed;  // the wall time the run clock stands for
    const auto ready = worker_.ready_at(due);
    if (!ready || *ready > due) return std::nullopt;
    return worker_.poll();
  }

 private:
  JobThread<Result> worker_;
  std::function<double()> run_clock_;
  struct {
    double run = 0;
    typename Clock::time_point wall;
  } submitted_;
};

}  // namespace fsd
