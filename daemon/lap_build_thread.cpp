#include "daemon/lap_build_thread.hpp"

#include <exception>
#include <utility>

namespace fsd {

LapBuildThread::LapBuildThread() : thread_([this] { run(); }) {}

LapBuildThread::~LapBuildThread() {
  {
    std::lock_guard lock(m_);
    stop_ = true;
  }
  cv_.notify_all();
  thread_.join();
}

bool LapBuildThread::submit(LapBuildJob job) {
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

std::optional<TrajectoryResult> LapBuildThread::poll() {
  std::lock_guard lock(m_);
  if (!result_) return std::nullopt;
  busy_ = false;
  return std::exchange(result_, std::nullopt);
}

void LapBuildThread::run() {
  std::unique_lock lock(m_);
  for (;;) {
    cv_.wait(lock, [this] { return stop_ || job_; });
    if (stop_) return;
    LapBuildJob job = std::move(*job_);
    job_.reset();
    lock.unlock();
    TrajectoryResult r;
    try {
      r = job();
    } catch (const std::exception& e) {  // a failed build is reported by the autopilot, not fatal here
      r.reason = e.what();
    }
    lock.lock();
    result_ = std::move(r);
  }
}

}  // namespace fsd
