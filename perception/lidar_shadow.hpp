#pragma once
// What nearer objects hide from the LiDAR: per azimuth step around the sensor, the range of the nearest obstacle
// return. A cone partly behind a nearer one (a row of cones in a tight turn, a cone behind a tyre) returns only
// from the azimuths that are not in that shadow; the size filter expects points of the part that shows, so that a
// cone half hidden is not rejected as too sparse for a whole cone.
#include <vector>

#include "common/types.hpp"

namespace fsd {

class LidarShadow {
 public:
  // `azimuth_step`: rad per bin (the sensor's horizontal step).
  explicit LidarShadow(double azimuth_step = 0.0034906585);
  // The nearest return per azimuth of `points` (any frame) seen from `sensor_xy` in the ground plane.
  void build(const std::vector<Point>& points, const Vec2& sensor_xy);
  // Share of the azimuths a disc of `radius` at `centre` covers that no return nearer than its front by more than
  // `margin` hides: 1 in the open, 0 wholly behind something.
  double visible_share(const Vec2& centre, double radius, double margin) const;

 private:
  int unwrapped_bin(double azimuth) const;  // from −π, may run past either end (a span across the seam)
  std::size_t wrap(int bin) const;          // into 0..bins_−1
  double step_;
  int bins_;
  Vec2 sensor_ = Vec2::Zero();
  std::vector<float> nearest_;
};

}  // namespace fsd
