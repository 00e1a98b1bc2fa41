#pragma once
// Lap-1 planning (DESIGN.md §5b, paper §IV): the track's midline from the cones known so far.
// Delaunay-triangulate the cones, walk forward from the car from triangle to triangle through edges that join the
// two boundaries, keep the best few partial walks (beam search) by a cost on heading change, width consistency and
// boundary colours, then smooth the chosen edge midpoints into a path with curvature and a speed profile.
// Colours help but are not trusted: a known colour on the wrong side costs, unknown colours fall back to geometry
// (crossing edges of plausible track width, boundary sides kept consistent along the walk, boundaries that bend
// gently with cones a few metres apart). Where one boundary is missing over a stretch, the path runs half a
// width inside the other one. Work is bounded by the cone count, beam width and depth; the wall-clock time is
// measured and reported against the budget (the supervisor decides what a late plan means).
#include <string>
#include <vector>

#include "common/track.hpp"
#include "common/types.hpp"
#include "control/cone_clearance.hpp"
#include "control/path.hpp"
#include "control/speed_profile.hpp"
#include "control/tight_turn.hpp"

namespace fsd {

struct MidlinePlannerConfig {
  double range = 22.0;                   // m: cones farther from the car are ignored
  double behind = 3.0;                   // m: cones farther than this behind the rear axle are ignored
  int max_cones = 160;                   // nearest cones kept (bounds the work per plan)
  double merge_distance = 0.25;          // m: cones closer than this are one cone
  bool use_colours = true;               // false: colour-blind (every cone's side from geometry only)
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
  double max_score = 1.0;                // a best walk scoring worse (cost − length reward) is no plan
  double colour_check_margin = 1.0;      // a colour-blind walk this much better in geometry wins; < 0: no check
  int max_wrong_colours = 2;             // ... if it passes at most this many cones against their colour
  double ds = 0.25;                      // m: spacing of the output path
  double smoothing_wavelength = 5.0;     // m: ripples shorter than this are smoothed out
  double min_length = 3.0;               // m: shorter walks are a failed plan
  double fallback_below = 8.0;           // m: a walk shorter than this (along it) tries the single-boundary fallback
  double end_speed = 0.0;                // m/s: speed allowed at the end of the planned horizon
  double time_budget = 0.025;            // s: the caller counts a plan slower than this as late (a warning)
  TightTurnConfig tight_turn;            // the line through hairpins and other turns at the steering lock
  bool keep_clear = true;          // push the path off cones nearer than the body's half width (tight_turn's body)
  double keep_clear_window = 3.0;  // m: a push fades out over this either side of the cone
};

struct PlanResult {
  Path path;  // empty unless ok
  bool ok = false;
  std::string reason;            // why the plan failed, empty when ok
  bool single_boundary = false;  // planned half a width inside one boundary (the other one is missing)
  bool ignored_colours = false;  // colours contradicted the geometry; planned colour-blind
  int cones_used = 0;
  int triangles = 0;
  std::vector<Vec2> midpoints;          // the chosen crossing-edge midpoints, map frame (for display)
  std::optional<TightTurn> tight_turn;  // the turn whose line was shaped to the car, map frame
};

class MidlinePlanner {
 public:
  MidlinePlanner(MidlinePlannerConfig config, ColourConvention convention, SpeedLimits limits);

  // Plans from `state` (map frame) through `cones` (map frame, any colour). Never throws on bad input:
  // non-finite cones are skipped and a failed plan says why.
  // `held_turn`: the tight turn the previous plan shaped (map frame), kept while the car is in it.
  PlanResult plan(const std::vector<Cone>& cones, const VehicleState& state,
                  const TightTurn* held_turn = nullptr) const;

  const MidlinePlannerConfig& config() const { return config_; }
  void set_config(const MidlinePlannerConfig& c) { config_ = c; }
  void set_speed_limits(const SpeedLimits& l) { speed_ = SpeedProfile(l); }
  const SpeedProfile& speed_profile() const { return speed_; }

 private:
  MidlinePlannerConfig config_;
  ColourConvention convention_;
  SpeedProfile speed_;
};

}  // namespace fsd
