#pragma once
// The estimated body poses of the last second or so, by time: what perception needs to place a LiDAR scan's
// points fired over 100 ms (deskew), to stack the last m scans (accumulation) and to move LiDAR candidates to the
// instant a camera frame was taken. Bounded: the oldest pose goes when a new one comes beyond capacity.
//
// Between two poses the position is interpolated linearly and the heading along the shorter arc; before the first
// and after the last pose the nearest one holds (a scan's last firing can be a few ms past the newest estimate).
#include <algorithm>
#include <cstddef>
#include <deque>
#include <functional>
#include <optional>

#include "common/geometry.hpp"
#include "common/time.hpp"

namespace fsd {

class PoseHistory {
 public:
  explicit PoseHistory(std::size_t capacity = 256) : capacity_(std::max<std::size_t>(capacity, 2)) {}

  // Poses come in time order; one older than the newest is ignored (a replayed or reordered estimate), one at the
  // same time replaces it.
  void add(Stamp t, const Pose2& pose) {
    if (!poses_.empty() && t < poses_.back().t) return;
    if (!poses_.empty() && t == poses_.back().t) {
      poses_.back().pose = pose;
      return;
    }
    if (poses_.size() == capacity_) poses_.pop_front();
    poses_.push_back({t, pose});
  }

  bool empty() const { return poses_.empty(); }
  std::size_t size() const { return poses_.size(); }
  void clear() { poses_.clear(); }
  // A loop closure corrected the estimates: each pose moves by `correction(its stamp)` (map ← estimated).
  void correct(const std::function<Pose2(Stamp)>& correction) {
    for (auto& s : poses_) s.pose = correction(s.t) * s.pose;
  }
  std::optional<Stamp> newest() const {
    if (poses_.empty()) return std::nullopt;
    return poses_.back().t;
  }
  // Whether the poses held go back to t (before the oldest, at() holds the oldest: no pose of that instant).
  bool reaches_back_to(Stamp t) const { return !poses_.empty() && poses_.front().t <= t; }

  // The pose at t; empty without any pose.
  std::optional<Pose2> at(Stamp t) const {
    if (poses_.empty()) return std::nullopt;
    if (t <= poses_.front().t) return poses_.front().pose;
    if (t >= poses_.back().t) return poses_.back().pose;
    const auto hi =
        std::lower_bound(poses_.begin(), poses_.end(), t, [](const Stamped& s, Stamp v) { return s.t < v; });
    const auto lo = hi - 1;
    const double u = (t - lo->t) / (hi->t - lo->t);
    const Pose2& a = lo->pose;
    const Pose2& b = hi->pose;
    return Pose2{a.x + u * (b.x - a.x), a.y + u * (b.y - a.y), wrap_angle(a.yaw + u * wrap_angle(b.yaw - a.yaw))};
  }

 private:
  struct Stamped {
    Stamp t;
    Pose2 pose;
  };
  std::size_t capacity_;
  std::deque<Stamped> poses_;
};

}  // namespace fsd
