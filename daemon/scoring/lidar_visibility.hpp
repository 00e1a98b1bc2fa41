#pragma once
// Which cones the simulated LiDAR could see at a perception frame (the scorecard's recall_visible_15m): those it
// sent at least `min_returns` returns from in the `window` up to the frame's last firing. The defaults are what
// the LiDAR stages can use: the 3 revolutions they accumulate (perception.lidar.accumulation.frames at 10 Hz) and
// the clusterer's 2 points (perception.lidar.cluster.min_points). A cone hidden behind a nearer one, below the
// lowest beam or in a LiDAR outage is not visible; one perception missed although it returned points is.
#include <cstddef>
#include <cstdint>
#include <deque>
#include <vector>

#include "common/time.hpp"
#include "daemon/feeders/truth_frames.hpp"

namespace fsd {

struct LidarVisibilityConfig {
  double window = 0.3;               // s up to the frame's last firing
  int min_returns = 2;               // returns from the cone in that window
  double keep = 2.0;                 // s of returns kept before the newest (detections come back late on a worker)
  std::size_t max_entries = 200000;  // bound of the kept entries, whatever the input
};

class LidarVisibility {
 public:
  explicit LidarVisibility(LidarVisibilityConfig cfg = {}) : cfg_(cfg) {}

  // The returns of a stretch of firings, in time order across calls (the simulator's TruthLidarReturns frames).
  void add(const std::vector<TruthLidarReturns>& returns);
  // Whether any returns were ever added (without the simulated LiDAR, nothing is known).
  bool known() const { return known_; }
  // The ids of the cones visible at `t` (a frame's last firing), sorted.
  std::vector<std::uint32_t> visible_at(Stamp t) const;

 private:
  LidarVisibilityConfig cfg_;
  std::deque<TruthLidarReturns> kept_;
  Stamp newest_ = -1e300;  // the newest return's time
  bool known_ = false;
};

}  // namespace fsd
