#pragma once
// One-to-one pairing of estimated and true cone positions, nearest pairs first, within a gate: how the scorecard
// judges the cone map and perception against the simulated world (a greedy global nearest neighbour).
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
