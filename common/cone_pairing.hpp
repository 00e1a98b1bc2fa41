#pragma once
// One-to-one pairing of estimated and reference cone positions, nearest pairs first, within a gate (a greedy global
// nearest neighbour): how the scorecard judges the cone map and perception against the simulated world, and how the
// LiDAR-alone localization pairs a frame's cones with the cone map (localization/map_match).
#include <cstddef>
#include <vector>

#include "common/geometry.hpp"

namespace fsd {

struct ConePair {
  std::size_t estimate, truth;
  double distance;
};

std::vector<ConePair> pair_cones(const std::vector<Vec2>& estimates, const std::vector<Vec2>& truths, double gate);

}  // namespace fsd
