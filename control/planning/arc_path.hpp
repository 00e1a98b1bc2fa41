#pragma once
// The optimizer's nodes as a path for the follower: the nodes themselves, and between each two the point on the arc of
// their mean curvature (the chord's middle moved out by the arc's sagitta κ·c²/8), so that the path is twice as dense;
// each point's curvature is its node's (the circle through it and its neighbouring nodes, which the optimizer bounded)
// or, between, the mean of the two.
#include <vector>

#include "common/geometry.hpp"
#include "control/planning/path.hpp"

namespace fsd {

// Geometry computed, speeds zero. Closed: round to the first node again.
Path arc_path(const std::vector<Vec2>& nodes, bool closed);

}  // namespace fsd
