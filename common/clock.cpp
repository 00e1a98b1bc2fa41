#include "common/clock.hpp"

#include <algorithm>

namespace fsd {

RealClock::RealClock() : epoch_(std::chrono::steady_clock::now()) {}

Stamp RealClock::now() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - epoch_).count();
}

bool RealClock::sleep_until(Stamp t) {
  const auto deadline =
      epoch_ + std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(t));
  std::unique_lock lock(m_);
  cv_.wait_until(lock, deadline, [&] { return stopped_; });
  return !stopped_;
}

void RealClock::stop() {
  {
    std::lock_guard lock(m_);
    stopped_ = true;
  }
  cv_.notify_all();
}

bool RealClock::stopped() const {
  std::lock_guard lock(m_);
  return stopped_;
}

SimulatedClock::SimulatedClock(double rate, Stamp start) : rate_(rate > 0 ? rate : 1.0), start_(start) {}

Stamp SimulatedClock::now() const { return start_ + rate_ * real_.now(); }

bool SimulatedClock::sleep_until(Stamp t) { return real_.sleep_until((t - start_) / rate_); }

void SimulatedClock::stop() { real_.stop(); }

bool SimulatedClock::stopped() const { return real_.stopped(); }

Stamp LockstepClock::now() const {
  std::lock_guard lock(m_);
  return now_;
}

bool LockstepClock::sleep_until(Stamp t) {
  std::unique_lock lock(m_);
  cv_.wait(lock, [&] { return stopped_ || now_ >= t; });
  return !stopped_;
}

void LockstepClock::stop() {
  {
    std::lock_guard lock(m_);
    stopped_ = true;
  }
  cv_.notify_all();
}

bool LockstepClock::stopped() const {
  std::lock_guard lock(m_);
  return stopped_;
}

void LockstepClock::advance_to(Stamp t) {
  {
    std::lock_guard lock(m_);
    now_ = std::max(now_, t);
  }
  cv_.notify_all();
}

}  // namespace fsd
