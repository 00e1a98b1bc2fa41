#include "perception/ground_split.hpp"

namespace fsd {

GroundSplitCounts split_by_ground(const std::vector<Point>& points, const GroundPlane& plane, double threshold,
                                  double max_height, std::vector<Point>* ground, std::vector<Point>& obstacles) {
  GroundSplitCounts c;
  const double k = plane.inv_norm();
  for (const auto& q : points) {
    const double d = (q.z - plane.z_at(q.x, q.y)) * k;
    if (d < -threshold) {
      ++c.below;
    } else if (d < threshold) {
      ++c.ground;
      if (ground) ground->push_back(q);
    } else if (d <= max_height) {
      ++c.obstacles;
      obstacles.push_back(q);
    } else {
      ++c.above;
    }
  }
  return c;
}

}  // namespace fsd
