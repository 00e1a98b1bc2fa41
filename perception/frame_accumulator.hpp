#pragma once
// Stage 3, accumulation of the last m frames (paper §III.A.2, eq. 6–8): each frame's obstacle points, already
// deskewed into the body frame at the frame's reference time, are kept with the body pose then (odometry/map ←
// body); the accumulated cloud is every kept frame moved into the current body frame, X̂ = T̂⁻¹ T_k X (eq. 7 with
// poses as isometries). Memory is bounded: at most `frames` frames of at most `max_points_per_frame` points.
#include <cstddef>
#include <deque>
#include <vector>

#include "common/config.hpp"
#include "common/types.hpp"

namespace fsd {

struct AccumulationConfig {
  int frames = 3;                    // m, the current frame included (1 = no accumulation)
  int max_points_per_frame = 20000;  // obstacle points kept per frame (the rest of a frame is dropped, counted)
  int deskew_knots = 10;             // pose samples per scan for the per-point motion compensation
};
const ConfigSection<AccumulationConfig>& accumulation_section();  // "perception.lidar.accumulation"

class FrameAccumulator {
 public:
  explicit FrameAccumulator(const AccumulationConfig& cfg = {}) : cfg_(cfg) {}

  // Adds a frame (points in the body frame at its reference time, body pose `odom_from_body` then) and drops the
  // oldest beyond m. Returns how many of its points were dropped by the per-frame bound.
  std::size_t add(const std::vector<Point>& points, const Pose3& odom_from_body);
  // Appends every kept frame's points, moved into the body frame of the newest frame, to `out`.
  void collect(std::vector<Point>& out) const;
  void clear() { frames_.clear(); }
  std::size_t frames() const { return frames_.size(); }

 private:
  struct Frame {
    Pose3 odom_from_body;
    std::vector<Point> points;
  };
  AccumulationConfig cfg_;
  std::deque<Frame> frames_;
};

}  // namespace fsd
