#pragma once
// The corridor ahead of the car from the cones seen so far (DESIGN.md §5b, paper §IV): Delaunay-triangulate the
// cones, walk forward from the car from triangle to triangle through edges that join the two boundaries, keep the
// best few partial walks (beam search) by a cost on heading change, width consistency and boundary colours. The walk
// gives the track's topology: the gates it crossed (their midpoints) and the cones it passed on each side, in order.
// The path optimizer (control/planning/path_optimizer.hpp) then finds where in that corridor the car drives.
// Colours help but are not trusted: a known colour on the wrong side costs, unknown colours fall back to geometry
// (crossing edges of plausible track width, boundary sides kept consistent along the walk, boundaries that bend
// gently with cones a few metres apart); a colour-blind walk that is clearly better wins. Where one boundary is
// missing over a stretch, the walk runs half a width inside the other one. Work is bounded by the cone count,
// beam width and depth.
#include <vector>

#include "common/geometry.hpp"

namespace fsd {

struct CorridorWalkConfig {
  double width_min = 2.5;                // m: shortest crossing edge
  double width_max = 6.5;                // m: longest crossing edge unless its colours say left–right
  double crossing_max = 7.0;             // m: longest crossing edge between a known left and a known right cone
  double nominal_width = 3.5;            // m: expected track width before the walk has measured it
  double start_radius = 7.0;             // m: the first crossing edge lies within this distance ahead of the car
  double start_angle_deg = 70.0;         // ... and within this bearing of the heading
  double max_turn_deg = 80.0;            // largest heading change from one midpoint to the next
  double min_crossing_cos = 0.5;         // a crossing edge's width across the travel direction over its length
  double horizon = 30.0;                 // m: walks stop growing at this length
  int beam_width = 16;                   // partial walks kept per step
  int max_depth = 80;                    // steps per walk
  double w_turn = 1.0;                   // cost per rad² of heading change
  double w_width = 0.5;                  // cost per squared relative width change
  double w_unknown = 0.05;               // cost per cone of unknown side crossed
  double w_colour_conflict = 3.0;        // cost per cone whose colour says the other side
  double w_boundary_bend = 4.0;          // cost per rad² of boundary bend beyond the free bend
  double boundary_free_bend_deg = 60.0;  // bend of a boundary from one cone to the next that costs nothing
  double w_boundary_gap = 0.1;           // cost per m² of boundary cone spacing beyond boundary_spacing_max
  double boundary_spacing_max = 5.5;     // m: FS boundaries have cones at most 5 m apart
  double w_length = 0.2;                 // reward per metre of walk
  double w_start = 0.05;                 // cost per metre from the car to the first midpoint
  double max_score = 1.0;                // a best walk scoring worse (cost − length reward) is no walk
  bool use_colours = true;               // false: colour-blind (every cone's side from geometry only)
  double colour_check_margin = 1.0;      // a colour-blind walk this much better in geometry wins; < 0: no check
  int max_wrong_colours = 2;             // ... if it passes at most this many cones against their colour
  double fallback_below = 8.0;           // m: a walk shorter than this (along it) tries the single-boundary fallback
};

// A cone in the car's frame (x forward from the rear axle, y left) and the side its colour names: +1 left, −1 right,
// 0 unknown.
struct WalkCone {
  Vec2 p = Vec2::Zero();
  int side = 0;
};

struct CorridorWalk {
  std::vector<Vec2> mids;         // the crossed gates' midpoints, in order from the car (the car's frame)
  std::vector<Vec2> left, right;  // the cones passed on each side, in order (single boundary: one of them empty)
  bool single_boundary = false;   // half a width inside the only boundary seen
  bool ignored_colours = false;   // colours contradicted the geometry: walked colour-blind
  int triangles = 0;
};

// The walk from the car (the origin, heading +x) through `cones` (merged, nearest first). Empty mids: no gate ahead.
CorridorWalk walk_corridor(const std::vector<WalkCone>& cones, const CorridorWalkConfig& config);

// Length of a polyline from the origin through `points`.
double length_from_origin(const std::vector<Vec2>& points);

}  // namespace fsd
