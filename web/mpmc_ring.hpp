#pragma once
// A bounded multi-producer multi-consumer ring (D. Vyukov's design): push and pop are a few atomic operations
// and never block, so a real-time thread can hand over data without waiting for the consumer. A full ring
// refuses the push (the caller counts it).
#include <atomic>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <utility>

namespace fsd::web {

template <class T>
class MpmcRing {
 public:
  explicit MpmcRing(std::size_t capacity)
      : size_(std::bit_ceil(capacity < 2 ? std::size_t{2} : capacity)),
        mask_(size_ - 1),
        cells_(std::make_unique<Cell[]>(size_)) {
    for (std::size_t i = 0; i < size_; ++i) cells_[i].seq.store(i, std::memory_order_relaxed);
  }

  // False when the ring is full; never waits.
  bool try_push(T value) {
    std::size_t pos = head_.load(std::memory_order_relaxed);
    for (;;) {
      Cell& c = cells_[pos & mask_];
      const std::size_t seq = c.seq.load(std::memory_order_acquire);
      const auto dif = static_cast<std::intptr_t>(seq) - static_cast<std::intptr_t>(pos);
      if (dif == 0) {
        if (head_.compare_exchange_weak(pos, pos + 1, std::memory_order_relaxed)) {
          c.value = std::move(value);
          c.seq.store(pos + 1, std::memory_order_release);
          return true;
        }
      } else if (dif < 0) {
        return false;
      } else {
        pos = head_.load(std::memory_order_relaxed);
      }
    }
  }

  // False when empty.
  bool try_pop(T& out) {
    std::size_t pos = tail_.load(std::memory_order_relaxed);
    for (;;) {
      Cell& c = cells_[pos & mask_];
      const std::size_t seq = c.seq.load(std::memory_order_acquire);
      const auto dif = static_cast<std::intptr_t>(seq) - static_cast<std::intptr_t>(pos + 1);
      if (dif == 0) {
        if (tail_.compare_exchange_weak(pos, pos + 1, std::memory_order_relaxed)) {
          out = std::move(c.value);
          c.value = T{};
          c.seq.store(pos + size_, std::memory_order_release);
          return true;
        }
      } else if (dif < 0) {
        return false;
      } else {
        pos = tail_.load(std::memory_order_relaxed);
      }
    }
  }

  std::size_t capacity() const { return size_; }
  // Items pushed and not yet popped; a snapshot that may be stale by the time it is read (for metrics).
  std::size_t approx_size() const {
    const std::size_t tail = tail_.load(std::memory_order_relaxed), head = head_.load(std::memory_order_relaxed);
    return head > tail ? head - tail : 0;
  }

 private:
  struct Cell {
    std::atomic<std::size_t> seq;
    T value;
  };
  const std::size_t size_, mask_;
  std::unique_ptr<Cell[]> cells_;
  alignas(64) std::atomic<std::size_t> head_{0};
  alignas(64) std::atomic<std::size_t> tail_{0};
};

}  // namespace fsd::web
