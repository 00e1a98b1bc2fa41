#pragma once
// One thread of its own that runs one job at a time for a caller that must not wait for it (the control thread):
// submit() hands a job over, poll() takes its result once. The thread is started with the object and joined by its
// destructor, which waits for a job under way to end (jobs cannot be interrupted midway; they are bounded).
// The workers of the Stack's slow, once-a-lap jobs (LapBuildThread, LoopSolveThread) are this.
#include <condition_variable>
#include <exception>
#include <functional>
#include <mutex>
#include <optional>
#include <thread>
#include <utility>

#include "common/job_service.hpp"

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

  // The submitted job's result, once, when it is ready; nullopt while it still runs (or with nothing out).
  std::optional<Result> poll() {
    std::lock_guard lock(m_);
    if (!result_) return std::nullopt;
    busy_ = false;
    return std::exchange(result_, std::nullopt);
  }

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
    }
  }

  std::function<Result(const std::exception&)> failed_;
  std::mutex m_;
  std::condition_variable cv_;
  std::optional<Job> job_;
  std::optional<Result> result_;
  bool busy_ = false, stop_ = false;
  std::thread thread_;  // last: started once the members it uses are
};

// A JobService whose jobs run on a JobThread: LapBuildThread, LoopSolveThread.
template <class Result>
class JobServiceThread : public JobService<Result> {
 public:
  explicit JobServiceThread(std::function<Result(const std::exception&)> failed) : worker_(std::move(failed)) {}
  bool submit(typename JobService<Result>::Job job) override { return worker_.submit(std::move(job)); }
  std::optional<Result> poll() override { return worker_.poll(); }

 private:
  JobThread<Result> worker_;
};

}  // namespace fsd
