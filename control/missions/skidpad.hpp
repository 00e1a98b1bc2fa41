#pragma once
// The skid pad's figure of eight from its cones. Each circle is marked by an inner and an outer ring of
// cones; both rings of one circle share a centre, found by a linear least-squares fit of two concentric
// circles. The driven path (Formula Student sequence): straight entry to the crossing between the circles,
// the right circle twice (clockwise), the left circle twice (counter-clockwise), straight exit. The driven
// radius is half the distance between the centres, so both circles pass through the crossing.
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "common/track.hpp"
#include "common/types.hpp"
#include "control/planning/path.hpp"

namespace fsd {

struct SkidpadCircle {
  Vec2 centre = Vec2::Zero();
  double inner_radius = 0, outer_radius = 0;  // fitted rings
  int cones = 0;
  double centre_line_radius() const { return 0.5 * (inner_radius + outer_radius); }
};

struct SkidpadGeometry {
  SkidpadCircle right, left;
  Vec2 crossing = Vec2::Zero();  // midpoint between the centres
  Vec2 forward = Vec2::UnitX();  // entry direction at the crossing
};

// Fits the two circles from the cones (map frame) and the start pose (on the entry, heading in). Timing and
// lane cones (orange, big orange) are left out; cones are split into right and left circle by their side of
// the start heading. nullopt with a reason when a circle has too few cones or the fit is implausible.
std::optional<SkidpadGeometry> fit_skidpad(const std::vector<Cone>& cones, const Pose2& start,
                                           const ColourConvention& convention, std::string* reason = nullptr);

struct SkidpadPlan {
  Path path;
  // Arc lengths where the car passes the crossing: [0] entering the right circle, [1] right lap 1 done,
  // [2] right lap 2 done (entering the left circle), [3] left lap 1 done, [4] left lap 2 done (exit).
  std::array<double, 5> crossing_s{};
};

// The figure-of-eight path (open, speeds zero: the speed profile runs after) from the start pose's foot on the
// entry axis to exit_length past the crossing. The curvature steps at the crossing (straight → right circle,
// right → left, left → straight) are smoothed over about `transition` m: a steering actuator with a rate limit
// cannot follow a step, and the lag would carry the car wide by metres at the circle's speed. The smoothed path
// leaves the circles by a few centimetres around the crossing only.
SkidpadPlan skidpad_path(const SkidpadGeometry& g, const Pose2& start, double exit_length, double ds,
                         double transition = 6.0);

}  // namespace fsd
