#pragma once
// Lap 2's minimum-curvature line (the option beside the centre line; Braghin et al. 2008, Heilmeier et
// al. 2019): every point of the closed centre line moves along its normal by α_i, within the room the mapped
// boundaries leave the car there, so that Σκ_i², the line's squared curvature, is least (κ linearised as an
// offset curve's, re-linearised a few times). A convex QP with a box on each α, solved by ADMM with its matrix
// factored once. Not a minimum-time line, but close to one on a Formula Student track, where corners are short
// and the speed is set by their curvature.
#include <vector>

#include "control/path.hpp"

namespace fsd {

struct RacingLineResult {
  Path path;               // the line, at the input's spacing, geometry recomputed; speeds are not kept
  double max_offset = 0;   // m: the largest |α|
  bool converged = false;  // every ADMM pass met its tolerance (the line is inside the room either way)
};

// `room_left[i]`, `room_right[i]` (≥ 0): how far point i may move to its left and right. A closed path only;
// an open one, or sizes that differ, come back unchanged.
RacingLineResult minimum_curvature_line(const Path& centre, const std::vector<double>& room_left,
                                        const std::vector<double>& room_right);

}  // namespace fsd
