#pragma once
// The track's corridor along a path: its left and right boundaries as the polylines through the mapped cones
// beside the path, in their order along it. Shared by lap 2's recentring (the centre line between them) and its
// racing line (the room either side).
#include <optional>
#include <vector>

#include "common/track.hpp"
#include "common/types.hpp"
#include "control/planning/path.hpp"

namespace fsd {

struct BoundaryCone {
  double s;  // arc length of the cone's foot on the path
  Vec2 p;
};

struct Corridor {
  std::vector<BoundaryCone> left, right;  // sorted by s
};

// Cones within `reach` of the path; colour names the side, a cone without one is on the side of the path it stands
// unless it stands more than 0.5 m farther out than that side's named cones nearby (outside the boundary: left out).
Corridor corridor_along(const Path& path, const std::vector<Cone>& cones, const ColourConvention& convention,
                        double reach);

// Segments of a boundary or centre polyline longer than this many `reach` along the line jump over a gap in it.
inline constexpr double kMaxSpanInReach = 3.0;

// Closest point to p on the polyline `b` (sorted by s), among segments that reach within `window` of s along the
// path and are no gap: a boundary of another stretch of the track that passes nearby is not this one, and neither
// is a jump over missing cones.
std::optional<Vec2> closest_on_boundary(const std::vector<BoundaryCone>& b, const Path& path, double s, const Vec2& p,
                                        double window);

}  // namespace fsd
