#include "common/latency_stats.hpp"

#include <algorithm>
#include <cmath>

namespace fsd {

LatencyStats::LatencyStats(std::size_t capacity) : capacity_(capacity ? capacity : 1) {}

void LatencyStats::add(double seconds) {
  std::lock_guard lock(m_);
  ++count_;
  max_ = std::max(max_, seconds);
  if (samples_.size() < capacity_) {
    samples_.push_back(seconds);
    return;
  }
  // Reservoir sampling keeps each of the count_ samples with equal probability.
  std::uniform_int_distribution<std::uint64_t> pick(0, count_ - 1);
  const auto j = pick(rng_);
  if (j < capacity_) samples_[j] = seconds;
}

std::uint64_t LatencyStats::count() const {
  std::lock_guard lock(m_);
  return count_;
}

double LatencyStats::quantile(double q) const {
  std::lock_guard lock(m_);
  if (samples_.empty()) return 0.0;
  std::vector<double> s = samples_;
  const auto k = static_cast<std::size_t>(std::clamp(q, 0.0, 1.0) * static_cast<double>(s.size() - 1) + 0.5);
  std::nth_element(s.begin(), s.begin() + static_cast<std::ptrdiff_t>(k), s.end());
  return s[k];
}

double LatencyStats::max() const {
  std::lock_guard lock(m_);
  return max_;
}

}  // namespace fsd
