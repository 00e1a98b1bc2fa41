#pragma once
// Per-stage latency samples with percentiles, for the scorecard and /metrics. Bounded: beyond `capacity`
// samples it keeps a uniform reservoir (deterministic, seeded), so a long run costs fixed memory.
#include <cstdint>
#include <mutex>
#include <random>
#include <vector>

namespace fsd {

class LatencyStats {
 public:
  explicit LatencyStats(std::size_t capacity = 100000);
  void add(double seconds);
  std::uint64_t count() const;
  // q in [0, 1]; 0 when empty. Seconds.
  double quantile(double q) const;
  double max() const;

 private:
  mutable std::mutex m_;
  std::size_t capacity_;
  std::vector<double> samples_;
  std::uint64_t count_ = 0;
  double max_ = 0;
  std::mt19937_64 rng_{12345};
};

}  // namespace fsd
