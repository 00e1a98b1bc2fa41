#pragma once
// Lap 1 (and the fallback on later laps): a path planned again on every perception frame from the car through the
// cones mapped so far. The corridor walk (control/planning/corridor_walk.hpp) finds which way the track goes and its
// two boundaries; the path optimizer (control/planning/path_optimizer.hpp) places a path in that corridor that keeps
// the body clear of every cone, within the steering's lock and rate, starting at the car's pose and curvature; the
// body is then swept along the result and the path ends before the first place it would come too near a cone (a row
// across the lane, a gap the car does not fit). The speed profile stops at that end, with the braking latency.
// Never throws on bad input: non-finite cones are skipped and a failed plan says why.
#include <string>
#include <vector>

#include "common/track.hpp"
#include "common/types.hpp"
#include "control/planning/corridor_walk.hpp"
#include "control/planning/path.hpp"
#include "control/planning/path_config.hpp"
#include "control/planning/speed_profile.hpp"

namespace fsd {

struct PlannerConfig {
  double range = 22.0;           // m: cones farther from the car are ignored
  double behind = 3.0;           // m: cones farther than this behind the rear axle are ignored
  int max_cones = 160;           // nearest cones kept (bounds the work per plan)
  double merge_distance = 0.25;  // m: cones closer than this are one cone
  CorridorWalkConfig walk;
  double reference_wavelength = 3.0;  // m: the walk's midline is smoothed over this before it is optimized
  double ds = 0.25;                   // m: spacing of straight paths the missions make (lanes, run-outs)
  double free_from = 0.5;             // m ahead of the car before clearance is asked (the car stands where it is)
  double min_length = 3.0;            // m: a shorter clear path is a failed plan
  double end_speed = 0.0;             // m/s at the end of the plan (0: it stops there)
  double time_budget = 0.015;         // s: the caller counts a plan slower than this as late (a warning)
};

struct PlanResult {
  Path path;  // map frame, with speeds; empty unless ok
  bool ok = false;
  std::string reason;            // why the plan failed (or was cut short), empty when whole
  bool single_boundary = false;  // planned half a width inside one boundary (the other one is missing)
  bool ignored_colours = false;  // colours contradicted the geometry; planned colour-blind
  bool cut_short = false;        // the body would have come too near a cone further on: the path ends before
  double clearance = 0;          // m: the least clearance of the body along the path kept
  int cones_used = 0;
  int triangles = 0;
  int iterations = 0;           // of the optimizer
  std::vector<Vec2> midpoints;  // the walk's gate midpoints, map frame (for display)
};

class RealtimePlanner {
 public:
  RealtimePlanner(PlannerConfig config, PathConfig path, ColourConvention convention, SpeedLimits limits);

  // Plans from `state` (map frame; steering = the measured wheel angle) through `cones` (map frame, any colour).
  // `previous`: the plan made last (map frame), which the optimizer starts from where it still lies ahead: a plan
  // again a tenth of a second on is nearly the same, and starting there keeps consecutive plans in one family and
  // the solve short. The optimizer also starts from the corridor's midline alone when that one does not come out
  // clear, and the clear one (or the one clear the farthest) is kept.
  PlanResult plan(const std::vector<Cone>& cones, const VehicleState& state, const Path* previous = nullptr) const;

  const PlannerConfig& config() const { return config_; }
  void set_config(const PlannerConfig& c, const PathConfig& path);
  void set_speed_limits(const SpeedLimits& l) { speed_ = SpeedProfile(l); }
  const SpeedProfile& speed_profile() const { return speed_; }

 private:
  PlannerConfig config_;
  PathConfig path_;
  ColourConvention convention_;
  SpeedProfile speed_;
};

}  // namespace fsd
