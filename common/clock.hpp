#pragma once
// Clocks (DESIGN.md §4). Every component reads time through a Clock so that the same code runs on the car
// (RealClock), on the virtual car in real time or scaled (SimulatedClock) and headless as fast as the CPU
// allows (LockstepClock, advanced only by the stepping loop, which makes runs deterministic).
#include <chrono>
#include <condition_variable>
#include <mutex>

#include "common/time.hpp"

namespace fsd {

class Clock {
 public:
  virtual ~Clock() = default;
  virtual Stamp now() const = 0;
  // Blocks until now() >= t or stop() was called. Returns false once stopped.
  virtual bool sleep_until(Stamp t) = 0;
  bool sleep_for(Duration d) { return sleep_until(now() + d); }
  // Wakes every sleeper for shutdown; later sleeps return false at once.
  virtual void stop() = 0;
  virtual bool stopped() const = 0;
};

// Monotonic wall time, seconds since construction.
class RealClock final : public Clock {
 public:
  RealClock();
  Stamp now() const override;
  bool sleep_until(Stamp t) override;
  void stop() override;
  bool stopped() const override;

 private:
  std::chrono::steady_clock::time_point epoch_;
  mutable std::mutex m_;
  std::condition_variable cv_;
  bool stopped_ = false;
};

// Simulated time that runs at `rate` × real time from `start` (rate 1 = real time, 2 = twice as fast).
class SimulatedClock final : public Clock {
 public:
  explicit SimulatedClock(double rate = 1.0, Stamp start = 0.0);
  Stamp now() const override;
  bool sleep_until(Stamp t) override;
  void stop() override;
  bool stopped() const override;
  double rate() const { return rate_; }

 private:
  double rate_;
  Stamp start_;
  RealClock real_;
};

// Time that moves only when the owner calls advance_to(); sleepers wake when their time is reached.
class LockstepClock final : public Clock {
 public:
  explicit LockstepClock(Stamp start = 0.0) : now_(start) {}
  Stamp now() const override;
  bool sleep_until(Stamp t) override;
  void stop() override;
  bool stopped() const override;
  // Moves time forward (never backward) and wakes the sleepers that are due.
  void advance_to(Stamp t);

 private:
  mutable std::mutex m_;
  std::condition_variable cv_;
  Stamp now_;
  bool stopped_ = false;
};

}  // namespace fsd
