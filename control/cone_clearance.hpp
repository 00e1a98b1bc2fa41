#pragma once
// A smoothed midline cuts the inside of a short, sharp bend (a chicane's step, the turn out of the start gate)
// and can pass a cone closer than half the car's width. This pushes the path away from every cone nearer than
// `need` (half the body's width + a cone's base radius + a clearance), the push fading out over `window` either
// side of the cone along the path. With cones near on both sides the pushes meet in the middle: the path ends up
// as far from both as the gap allows.
#include <vector>

#include "common/geometry.hpp"
#include "control/path.hpp"

namespace fsd {

struct ConeClearance {
  int cones_too_near = 0;   // cones nearer than `need` before the repair
  double worst_before = 0;  // m: the largest shortfall before
  double worst_after = 0;   // m: ... and after (> 0: the gap is narrower than the car)
};

// `path` open, any frame, `cones` in the same frame. Points within `keep_start` of the path's start (the car)
// are not moved. Geometry (s, yaw, kappa) is recomputed; speeds are not.
ConeClearance keep_clear_of_cones(Path& path, const std::vector<Vec2>& cones, double need, double window,
                                  double keep_start = 1.5);

}  // namespace fsd
