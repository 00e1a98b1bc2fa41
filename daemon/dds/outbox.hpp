#pragma once
// The DDS bridge's one writer thread: producers (the control thread, a driver thread) post a job that converts
// and writes a message; the thread runs them in order. A post never waits: the queue is bounded and drops its
// oldest job when full (counted), so DDS being slow costs messages, never a control cycle (DESIGN.md §4). The
// thread runs at a lower priority (nice +10) than the rest of the daemon, so that on a busy computer the kernel
// gives a core to the control loop first. The destructor runs what is queued, then joins.
#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <functional>
#include <thread>

#include "common/bounded_queue.hpp"

namespace fsd::dds {

class Outbox {
 public:
  explicit Outbox(std::size_t capacity) : jobs_(capacity), thread_([this] { loop(); }) {}
  ~Outbox() { stop(); }
  Outbox(const Outbox&) = delete;
  Outbox& operator=(const Outbox&) = delete;

  // False when the job pushed out an older one (or the outbox has stopped).
  bool post(std::function<void()> job) { return jobs_.push(std::move(job)); }
  // Runs what is queued, then ends the thread. Idempotent.
  void stop() {
    stopping_.store(true);
    jobs_.close();
    if (thread_.joinable()) thread_.join();
  }
  std::uint64_t dropped() const { return jobs_.dropped(); }
  std::uint64_t done() const { return done_.load(std::memory_order_relaxed); }

 private:
  void loop() {
    // This thread only (Linux: a thread's nice value is its own); failure leaves it at the daemon's priority.
    ::setpriority(PRIO_PROCESS, static_cast<id_t>(::syscall(SYS_gettid)), ::getpriority(PRIO_PROCESS, 0) + 10);
    for (;;) {
      auto job = jobs_.pop_for(std::chrono::milliseconds(200));
      if (!job) {
        if (stopping_.load()) return;  // closed: pop_for hands out what was queued before it says nothing
        continue;
      }
      (*job)();
      done_.fetch_add(1, std::memory_order_relaxed);
    }
  }
  BoundedQueue<std::function<void()>> jobs_;
  std::atomic<std::uint64_t> done_{0};
  std::atomic<bool> stopping_{false};
  std::thread thread_;
};

}  // namespace fsd::dds
