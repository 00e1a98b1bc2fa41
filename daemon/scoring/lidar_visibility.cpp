#include "daemon/scoring/lidar_visibility.hpp"

#include <algorithm>
#include <map>

namespace fsd {

void LidarVisibility::add(const std::vector<TruthLidarReturns>& returns) {
  known_ = true;
  for (const auto& r : returns) {
    kept_.push_back(r);
    newest_ = std::max(newest_, r.t);
  }
  while (!kept_.empty() && (kept_.front().t < newest_ - cfg_.keep || kept_.size() > cfg_.max_entries))
    kept_.pop_front();
}

std::vector<std::uint32_t> LidarVisibility::visible_at(Stamp t) const {
  // The frame's own firings up to t (a hair of slack for the stamp's rounding), none after it.
  constexpr double kSlack = 1e-6;
  std::map<std::uint32_t, std::uint64_t> returns;
  for (const auto& r : kept_)
    if (r.t > t - cfg_.window && r.t <= t + kSlack) returns[r.id] += r.returns;
  std::vector<std::uint32_t> ids;
  for (const auto& [id, n] : returns)
    if (n >= static_cast<std::uint64_t>(cfg_.min_returns)) ids.push_back(id);
  return ids;  // sorted: std::map's order
}

}  // namespace fsd
