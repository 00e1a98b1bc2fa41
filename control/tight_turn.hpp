#pragma once
// The line through a tight turn (a hairpin at the rules' 9 m outside diameter, a tight 90°): there the car runs at
// or near full lock, and a midline path does not fit the car. The nose sweeps outside the rear axle's circle by
// √((R + w)² + f²) − R (front overhang f from the rear axle, half width w), so the outer cones bound the rear
// axle's radius R from above, the inner cones from below, and the steering lock from below too; on a 3 m lane
// around a 1.5 m inner radius the window is 2.80–2.97 m at a 0.5 rad lock. Such a turn is only driven cleanly on a
// circle concentric with the turn at a radius inside that window: this replaces the path through the turn by a
// straight, a clothoid (the rate-limited steering's turn-in), that arc, a clothoid and a straight back out. The turn's centre and lane radii come from a
// fit of two concentric rings to the cones inside and outside the turn, not from the path.
#include <optional>
#include <vector>

#include "common/geometry.hpp"
#include "control/path.hpp"

namespace fsd {

struct TightTurnConfig {
  bool enabled = true;
  double kappa_on = 0.15;        // 1/m: a turn is where the smoothed path curves tighter than this
  double min_turn_deg = 60.0;    // heading change of a turn worth shaping (the car already in it: any)
  double lane_radius_max = 5.0;  // m: only turns whose lane centre radius is below this are shaped
  double body_front = 2.4;       // m: rear axle to the nose
  double body_half_width = 0.7;  // m
  double cone_radius = 0.12;     // m: half a cone's base
  double clearance = 0.05;       // m: kept between body and cones
  double lock_margin = 0.02;     // the arc's curvature stays this share below the lock's
  double lock_authority = 0.04;  // ... and this share where the cones leave room (steering left to correct with)
  double lead = 5.0;             // m: the path is rejoined this far before and after the turn
  double transition_length =
      2.5;  // m: the turn-in and turn-out clothoids (steering rate × speed / wheelbase, and more)
  double smoothing_wavelength = 1.5;  // m: the joins with the path are rounded over about this
  // At the lock the follower has no steering left to correct with (a car carried wide stays wide), and the rejoin
  // can bend harder than the arc: the shaped stretch is driven at most this fast.
  double v_max = 5.0;  // m/s
  // On real-time plans (lap 1), no faster than the room the cones leave the rear axle's arc either side allows:
  // at a steering angle held for the arc a car that understeers runs wide by r·K·v²/L, kept within room_share of
  // that room; a turn that leaves none is driven at v_min. (Lap 2's line is planned once over the whole lap.)
  double understeer = 0.0036;  // rad per m/s² (K: δ = L/R + K·v²/R; the virtual car's, measured at the lock)
  double room_share = 0.5;
  double v_min = 2.0;  // m/s
  // Not in the configuration section: the steering's limits, from control.follower.
  double wheelbase = 1.53;  // m
  double max_steer = 0.5;   // rad
};

struct TightTurn {
  Vec2 centre = Vec2::Zero();
  double inner_radius = 0, outer_radius = 0;  // of the cone rings
  double outer_nearest = 0;                   // the nearest outer cone's distance from the centre (the nose's limit)
  double inner_farthest = 0;                  // the farthest inner cone's (the inner side's limit)
  double radius = 0;                          // of the rear axle's arc
  double room = 0;                            // m the arc may move either way before the body meets the cones
  double sweep = 0;                           // rad, the arc's angle (positive)
  int direction = 0;                          // +1 round to the left (counter-clockwise), −1 to the right
  Vec2 exit = Vec2::Zero();                   // where the turn-out ends (back on a straight) ...
  Vec2 exit_direction = Vec2::UnitX();        // ... heading this way (unit)
  double s_begin = 0, s_end = 0;              // m: the rebuilt stretch of the path, from leaving it to rejoining
};

// The speed a real-time plan drives `turn` at most: v_max, or less where its room is small (config above).
double room_speed(const TightTurn& turn, const TightTurnConfig& config);

// The turn in another frame: `by` (frame ← the turn's frame) applied to its centre and exit.
TightTurn transformed(TightTurn turn, const Pose2& by);

// Finds the tight turns along the open `path` (any frame; `cones` in the same frame) that the cones confirm, and
// rebuilds the path through each (turns back to back, an S of two hairpins, get one line). Returns the turns
// shaped, in path order. The path keeps its first point; its geometry (s, yaw, kappa) is recomputed, speeds are
// not (the speed profile runs after).
// `held`: the turn the previous plan shaped first (same frame). Until the car has passed the end of its turn-out
// the path is shaped round it again, whatever the midline beside the car does: past the middle of a hairpin the
// midline no longer curves enough to be found as a turn and the cones left ahead are too few to fit its rings, and
// falling back to the midline (the lane's middle, wider than the car's line) at the lock carries the nose into
// the outer cones.
std::vector<TightTurn> shape_tight_turns(Path& path, const std::vector<Vec2>& cones, const TightTurnConfig& config,
                                         const TightTurn* held = nullptr);

// The same for every tight turn of a closed lap (lap 2's trajectory); returns the turns shaped.
std::vector<TightTurn> shape_tight_turns_on_lap(Path& lap, const std::vector<Vec2>& cones,
                                                const TightTurnConfig& config);

}  // namespace fsd
