#pragma once
// Hand-over between threads (DESIGN.md §4): a bounded queue that drops the oldest item instead of blocking the
// producer, and a latest-value slot. Both count what they drop so the dashboard and /metrics can show it.
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <mutex>
#include <optional>

namespace fsd {

template <class T>
class BoundedQueue {
 public:
  explicit BoundedQueue(std::size_t capacity) : capacity_(capacity ? capacity : 1) {}

  // Never blocks: when full, the oldest item is dropped. Returns false if an item was dropped.
  bool push(T item) {
    bool dropped = false;
    {
      std::lock_guard lock(m_);
      if (closed_) return false;
      if (q_.size() >= capacity_) {
        q_.pop_front();
        dropped = true;
        dropped_.fetch_add(1, std::memory_order_relaxed);
      }
      q_.push_back(std::move(item));
    }
    cv_.notify_one();
    return !dropped;
  }

  // Waits up to `timeout` for an item; nullopt on timeout or when closed and empty.
  template <class Rep, class Period>
  std::optional<T> pop_for(std::chrono::duration<Rep, Period> timeout) {
    std::unique_lock lock(m_);
    cv_.wait_for(lock, timeout, [&] { return closed_ || !q_.empty(); });
    return take(lock);
  }
  std::optional<T> try_pop() {
    std::unique_lock lock(m_);
    return take(lock);
  }
  // Wakes every waiter; later pushes are refused.
  void close() {
    {
      std::lock_guard lock(m_);
      closed_ = true;
    }
    cv_.notify_all();
  }
  std::size_t size() const {
    std::lock_guard lock(m_);
    return q_.size();
  }
  std::size_t capacity() const { return capacity_; }
  std::uint64_t dropped() const { return dropped_.load(std::memory_order_relaxed); }

 private:
  std::optional<T> take(std::unique_lock<std::mutex>&) {
    if (q_.empty()) return std::nullopt;
    T item = std::move(q_.front());
    q_.pop_front();
    return item;
  }
  const std::size_t capacity_;
  mutable std::mutex m_;
  std::condition_variable cv_;
  std::deque<T> q_;
  bool closed_ = false;
  std::atomic<std::uint64_t> dropped_{0};
};

// Holds the latest value written; readers get a copy and a sequence number to tell new from seen.
template <class T>
class LatestValue {
 public:
  void set(T v) {
    std::lock_guard lock(m_);
    value_ = std::move(v);
    ++seq_;
  }
  std::optional<T> get() const {
    std::lock_guard lock(m_);
    return value_;
  }
  // Copies the value if it is newer than `seen` and updates `seen`.
  std::optional<T> get_if_newer(std::uint64_t& seen) const {
    std::lock_guard lock(m_);
    if (seq_ == seen || !value_) return std::nullopt;
    seen = seq_;
    return value_;
  }
  std::uint64_t seq() const {
    std::lock_guard lock(m_);
    return seq_;
  }

 private:
  mutable std::mutex m_;
  std::optional<T> value_;
  std::uint64_t seq_ = 0;
};

}  // namespace fsd
