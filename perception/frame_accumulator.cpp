#include "perception/frame_accumulator.hpp"

#include <algorithm>

namespace fsd {

const ConfigSection<AccumulationConfig>& accumulation_section() {
  static const auto s = ConfigSection<AccumulationConfig>("perception.lidar.accumulation")
                            .integer("frames", &AccumulationConfig::frames, 1, 20, "",
                                     "Frames accumulated (m, paper eq. 6-8), the current one included; 1 = none.")
                            .integer("max_points_per_frame", &AccumulationConfig::max_points_per_frame, 100, 1000000,
                                     "", "Obstacle points kept per frame (bounds memory and time).")
                            .integer("deskew_knots", &AccumulationConfig::deskew_knots, 1, 1000, "",
                                     "Pose samples per scan for the per-point motion compensation.");
  return s;
}

std::size_t FrameAccumulator::add(const std::vector<Point>& points, const Pose3& odom_from_body) {
  const auto cap = static_cast<std::size_t>(std::max(1, cfg_.max_points_per_frame));
  Frame f{odom_from_body, {}};
  if (points.size() <= cap) {
    f.points = points;
  } else {
    // An even subsample, so that a crowded frame keeps its whole extent.
    f.points.reserve(cap);
    for (std::size_t k = 0; k < cap; ++k) f.points.push_back(points[k * points.size() / cap]);
  }
  frames_.push_back(std::move(f));
  while (frames_.size() > static_cast<std::size_t>(std::max(1, cfg_.frames))) frames_.pop_front();
  return points.size() - frames_.back().points.size();
}

void FrameAccumulator::collect(std::vector<Point>& out) const {
  if (frames_.empty()) return;
  const Pose3 now_inv = frames_.back().odom_from_body.inverse();
  for (const auto& f : frames_) {
    if (&f == &frames_.back()) {
      out.insert(out.end(), f.points.begin(), f.points.end());
      continue;
    }
    const Pose3 M = now_inv * f.odom_from_body;  // body(now) ← body(then)
    const Eigen::Matrix3f R = M.linear().cast<float>();
    const Eigen::Vector3f t = M.translation().cast<float>();
    for (Point q : f.points) {
      const Eigen::Vector3f p = R * Eigen::Vector3f(q.x, q.y, q.z) + t;
      q.x = p.x(), q.y = p.y(), q.z = p.z();
      out.push_back(q);
    }
  }
}

}  // namespace fsd
