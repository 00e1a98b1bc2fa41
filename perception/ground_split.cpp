#include "perception/ground_split.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace fsd {

void GroundSplitter::classify(const std::vector<Point>& points, const GroundSurface& ground, double threshold,
                              double max_height) {
  height_.resize(points.size());
  kind_.resize(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto& q = points[i];
    const double d = ground.height_of(q.x, q.y, q.z);
    height_[i] = static_cast<float>(d);
    kind_[i] = d < -threshold    ? Kind::Below
               : d < threshold   ? Kind::Ground
               : d <= max_height ? Kind::Obstacle
                                 : Kind::Above;
  }
}

std::size_t GroundSplitter::mark_grazing(const std::vector<Point>& points, const GroundSurface& ground,
                                         double threshold, const GrazingBeams& g) {
  const double sensor_h = ground.height_of(g.sensor.x(), g.sensor.y(), g.sensor.z());
  if (g.band <= 0 || sensor_h <= threshold) return 0;
  // The band is longer than g.band along the beam where sin(grazing angle) < threshold / band, i.e. beyond this
  // horizontal range from the sensor (flat-ground approximation: sin β ≈ h / r).
  const double min_range = sensor_h * g.band / threshold;
  const float min_range2 = static_cast<float>(min_range * min_range);
  by_ring_.resize(256);
  for (auto& r : by_ring_) r.clear();
  const float sx = static_cast<float>(g.sensor.x()), sy = static_cast<float>(g.sensor.y());
  // Band points per laser, in firing (azimuth) order; the grazing ones are tested, all serve as neighbours.
  for (std::uint32_t i = 0; i < points.size(); ++i)
    if (kind_[i] == Kind::Ground) by_ring_[points[i].ring & 0xFF].push_back(i);
  std::size_t found = 0;
  constexpr double kTwoPi = 2 * std::numbers::pi;
  for (const auto& ring : by_ring_) {
    // The ring is circular: a revolution's first and last firings are neighbours (the frame cut is often straight
    // ahead); the azimuth window stops the walk on a partial scan.
    const std::size_t n = ring.size();
    for (std::size_t k = 0; k < n; ++k) {
      const Point& p = points[ring[k]];
      const float dx = p.x - sx, dy = p.y - sy;
      if (dx * dx + dy * dy < min_range2) continue;  // steep enough: the height test holds
      // A return of the laser farther by the drop within the window on each side: an object narrower than the
      // window is short of the ground beyond it on both sides, however many of its own points the window holds;
      // a ground ring whose range trends along the azimuth (a pitched sensor, a slope) is short of one side only.
      const auto keep = static_cast<float>(1.0 - g.drop);
      const float beyond = p.distance / keep;  // a ground return this far on the side shows p stands short of it
      const auto side_has_far = [&](bool left) {
        int count = 0;
        bool far = false;
        for (std::size_t step = 1; step < n; ++step) {
          const Point& q = points[ring[left ? (k + n - step) % n : (k + step) % n]];
          double da = std::abs(q.azimuth - p.azimuth);
          da = std::min(da, kTwoPi - da);
          if (da > g.window) break;
          ++count;
          far = far || q.distance > beyond;
          if (far && count * 2 >= g.min_neighbours) return true;
        }
        return false;
      };
      if (!side_has_far(true) || !side_has_far(false)) continue;
      kind_[ring[k]] = Kind::Obstacle;
      ++found;
    }
  }
  return found;
}

}  // namespace fsd
