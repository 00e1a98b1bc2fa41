#include "perception/lidar_shadow.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace fsd {

LidarShadow::LidarShadow(double azimuth_step)
    : step_(std::max(azimuth_step, 1e-4)),
      bins_(static_cast<int>(std::ceil(2 * std::numbers::pi / step_))),
      nearest_(static_cast<std::size_t>(bins_), std::numeric_limits<float>::max()) {}

int LidarShadow::unwrapped_bin(double azimuth) const {
  return static_cast<int>(std::floor((azimuth + std::numbers::pi) / step_));
}

std::size_t LidarShadow::wrap(int bin) const { return static_cast<std::size_t>(((bin % bins_) + bins_) % bins_); }

void LidarShadow::build(const std::vector<Point>& points, const Vec2& sensor_xy) {
  sensor_ = sensor_xy;
  std::fill(nearest_.begin(), nearest_.end(), std::numeric_limits<float>::max());
  for (const auto& q : points) {
    const double dx = q.x - sensor_xy.x(), dy = q.y - sensor_xy.y();
    float& n = nearest_[wrap(unwrapped_bin(std::atan2(dy, dx)))];
    n = std::min(n, static_cast<float>(std::hypot(dx, dy)));
  }
}

double LidarShadow::visible_share(const Vec2& centre, double radius, double margin) const {
  const Vec2 d = centre - sensor_;
  const double range = d.norm();
  if (range <= radius) return 1.0;
  const double half = std::asin(radius / range), mid = std::atan2(d.y(), d.x());
  const double front = range - radius - margin;
  int open = 0, all = 0;
  for (int b = unwrapped_bin(mid - half), last = unwrapped_bin(mid + half); b <= last; ++b, ++all)
    open += nearest_[wrap(b)] >= front;
  return all > 0 ? static_cast<double>(open) / all : 1.0;
}

}  // namespace fsd
