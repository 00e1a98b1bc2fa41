#pragma once
// Lap 2 (paper §IV): the trajectory the car drove on lap 1, recorded pose by pose, closed at the loop,
// resampled and smoothed, optionally pulled onto the centre of the mapped corridor, with a speed at every
// waypoint from the lap's forward–backward pass. Followed on the fused GNSS-INS pose.
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "common/track.hpp"
#include "common/types.hpp"
#include "control/path.hpp"
#include "control/speed_profile.hpp"
#include "control/tight_turn.hpp"

namespace fsd {

struct RecordedTrajectoryConfig {
  double sample_spacing = 0.3;         // m between recorded poses
  int max_samples = 20000;             // bound on memory (6 km at the default spacing)
  double ds = 0.25;                    // m, spacing of the lap path
  double smoothing_wavelength = 12.0;  // m: ripples of the driven line shorter than this are smoothed out
  double max_closure_gap = 6.0;        // m: the recorded lap's end must come back this close to its start
  double min_lap_length = 30.0;        // m
  bool recentre = true;                // pull the line to the middle of the mapped cones
  double recentre_reach = 4.0;         // m: cones this far along and across the line count for its corridor
  double max_centre_offset = 0.35;     // m: the recentred lap, smoothed, stays this close to the centre line; 0 = free
  // "centre": lap 2 on the centre line (what the scorecard's cross-track error measures); "min_curvature": the
  // flattest line within the mapped boundaries, each cone's line kept `racing_keep` from the car's path.
  std::string line = "centre";
  double racing_keep = 1.2;            // m: half the body (0.7) + a cone's radius (0.12) + what tracking may stray
  double early_build_distance = 25.0;  // m: lap 1's path is built and taken this far before the line (0: at it)
  TightTurnConfig tight_turn;  // turns at the steering lock get the car's line (control.tight_turn), as on lap 1
};

struct TrajectoryResult {
  std::optional<Path> path;      // closed lap with speeds, or nothing
  std::string reason;            // why not, when empty
  double closure_gap = 0;        // m
  double recentre_rms = 0;       // m, how far recentring moved the line
  double racing_offset = 0;      // m: the min-curvature line's largest move off the centre line
  std::vector<SpeedZone> zones;  // the speed caps its profile was computed with (tight turns): kept for re-profiling
};

class RecordedTrajectory {
 public:
  explicit RecordedTrajectory(RecordedTrajectoryConfig config = {}) : config_(config) {}

  void record(const VehicleState& state);  // every pose of lap 1; keeps one per sample_spacing
  void clear() { samples_.clear(); }
  // A loop closure corrected the poses recorded so far: each sample moves by `correction(its stamp)`. Returns the
  // largest move (m).
  double relocate(const std::function<Pose2(Stamp)>& correction);
  std::size_t size() const { return samples_.size(); }

  // The closed lap from the samples stamped within [t0, t1] (the lap's line crossings, or the run start).
  // `map_cones` (map frame) are used for recentring when enabled; may be empty.
  // `ahead` (optional): the planned line from the car on, appended to close a lap that is not yet complete (the
  // lap path is built shortly before the line, so that the car crosses it at the lap's speed).
  TrajectoryResult build(Stamp t0, Stamp t1, const std::vector<Cone>& map_cones, const ColourConvention& convention,
                         const SpeedProfile& speed, const std::vector<Vec2>& ahead = {}) const;

  const RecordedTrajectoryConfig& config() const { return config_; }

 private:
  struct Sample {
    Stamp t;
    Vec2 p;
  };
  RecordedTrajectoryConfig config_;
  std::vector<Sample> samples_;
};

// Moves every point of a path onto the track's centre line: the boundaries are the polylines through the mapped
// cones on its left and on its right (each cone within `reach` of the path, in their order along it), the centre
// line runs half way between each point of the left boundary and its closest point on the right one (the
// scorecard's definition, DESIGN.md §8). Returns the RMS shift. Points with no centre line within `reach` stay.
double recentre_on_cones(Path& path, const std::vector<Cone>& cones, const ColourConvention& convention, double reach);

}  // namespace fsd
