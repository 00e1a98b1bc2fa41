#pragma once
// The ground stage's output: each point of the cropped cloud is ground (within τ of the plane), an obstacle point
// (between τ and the region's height limit above it), below the ground (noise, reflections: dropped) or above the
// region of interest (dropped).
#include <cstddef>
#include <vector>

#include "common/types.hpp"
#include "perception/ground_plane.hpp"

namespace fsd {

struct GroundSplitCounts {
  std::size_t ground = 0, obstacles = 0, below = 0, above = 0;
};

// Appends the obstacle points to `obstacles` and, when `ground` is not null, the ground points to it.
GroundSplitCounts split_by_ground(const std::vector<Point>& points, const GroundPlane& plane, double threshold,
                                  double max_height, std::vector<Point>* ground, std::vector<Point>& obstacles);

}  // namespace fsd
