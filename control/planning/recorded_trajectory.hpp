#pragma once
// Lap 2 (paper §IV): the trajectory the car drove on lap 1, recorded pose by pose, closed at the loop, resampled,
// smoothed and pulled onto the centre of the mapped corridor; then the whole lap at once through the path optimizer
// (control/planning/path_optimizer.hpp) on that centre line, in the room the mapped boundaries leave, the body kept
// clear of every mapped cone; with a speed at every waypoint from the lap's forward–backward pass. Followed on the
// fused GNSS-INS pose. A lap whose line would not keep the body clear is refused (the real-time plans drive on).
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "common/track.hpp"
#include "common/types.hpp"
#include "control/planning/path.hpp"
#include "control/planning/path_config.hpp"
#include "control/planning/speed_profile.hpp"

namespace fsd {

struct RecordedTrajectoryConfig {
  double sample_spacing = 0.3;         // m between recorded poses
  int max_samples = 20000;             // bound on memory (6 km at the default spacing)
  double ds = 0.25;                    // m, spacing of the lap path
  double smoothing_wavelength = 12.0;  // m: ripples of the driven line shorter than this are smoothed out
  double max_closure_gap = 6.0;        // m: the recorded lap's end must come back this close to its start
  double min_lap_length = 10.0;        // m
  bool recentre = true;                // pull the line to the middle of the mapped cones
  double recentre_reach = 4.0;         // m: cones this far along and across the line count for its corridor
  // "centre": the optimizer kept near the centre line (control.path.w_centre; the scorecard's cross-track error is
  // measured against it); "min_curvature": the flattest line within the room the mapped boundaries leave.
  std::string line = "centre";
  double early_build_distance = 25.0;  // m: lap 1's path is built and taken this far before the line (0: at it)
  // Not configuration keys: the optimizer's settings and the car (control.path, car.*).
  PathConfig path;
};

struct TrajectoryResult {
  std::optional<Path> path;      // closed lap with speeds, or nothing
  std::string reason;            // why not, when empty
  double closure_gap = 0;        // m
  double recentre_rms = 0;       // m, how far recentring moved the line
  double clearance = 0;          // m: the least clearance of the body from a mapped cone round the lap
  double max_offset = 0;         // m: the line's largest move off the centre line
  int iterations = 0;            // of the optimizer
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
  // The optimizer's line round the closed `centre` in the mapped corridor; r.reason says why when it is not clear.
  Path line_through(const Path& centre, const std::vector<Cone>& map_cones, const ColourConvention& convention,
                    TrajectoryResult& r) const;

  RecordedTrajectoryConfig config_;
  std::vector<Sample> samples_;
};

// Moves every point of a path onto the track's centre line: the boundaries are the polylines through the mapped
// cones on its left and on its right (each cone within `reach` of the path, in their order along it), the centre
// line runs half way between each point of the left boundary and its closest point on the right one (the
// scorecard's definition, DESIGN.md §8). Returns the RMS shift. Points with no centre line within `reach` stay.
double recentre_on_cones(Path& path, const std::vector<Cone>& cones, const ColourConvention& convention, double reach);

}  // namespace fsd
