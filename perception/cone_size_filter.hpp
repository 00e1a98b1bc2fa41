#pragma once
// Stage 5, size filter (paper §III.A.3, beyond it where the sensor geometry allows): which clusters can be a cone
// (FSG small cone 228 × 228 × 325 mm, big orange cone 285 × 285 × 505 mm), and where a cone's base centre is.
//
// A cluster is measured in the ground plane along the sensor's line of sight (radial) and across it (tangential),
// with each point's height above the ground plane, and rejected when it is
//  - too wide: larger across or along the line of sight than a big cone's base plus a margin;
//  - too tall: its top is higher than a big cone's;
//  - not cone-shaped: at some height its silhouette across the line of sight is wider than a big cone's there
//    (a standing tyre's tread, a box);
//  - too flat: the laser above its top would have hit a cone (its next beam passes below a small cone's top at
//    that range), so the object is lower than a cone (a kerb, a lying tyre);
//  - floating: the laser below its bottom would have hit it above the ground threshold had it stood on the ground
//    (both only where the sensor has a laser above / below: its fan ends at lowest/highest_beam_deg, tilted with
//    the mount);
//  - too sparse: fewer points than a share of what a small cone returns at that range with this sensor, over the
//    azimuths that nearer objects do not hide (LidarShadow: a cone in a row behind another shows a part);
//  - beside something taller: obstacle points higher than any cone within `tall_clearance` of its position (the
//    sparse low fragments of a fence seen at a grazing angle, the foot of a post or a person).
// The laser spacing and azimuth step are the sensor's (VLP-16 defaults) and make the tests range-aware.
//
// Position: the tangential middle of the silhouette (the centre of a circle seen from afar) and, along the line
// of sight, each point's range plus the cone's depth behind it at its height, averaged; so the visible front half
// of the cone does not pull the position towards the sensor (by π/4 of the radius, ~7 cm on average). The radius
// at a height is the silhouette's measured half-width there, held between the small and the big cone model.
#include <cstdint>
#include <vector>

#include "common/config.hpp"
#include "common/types.hpp"
#include "perception/candidate.hpp"
#include "perception/clusterer.hpp"
#include "perception/ground_surface.hpp"
#include "perception/lidar_shadow.hpp"

namespace fsd {

struct ConeSizeConfig {
  double small_width = 0.228, small_height = 0.325;     // m, FSG small cone (blue, yellow, small orange)
  double big_width = 0.285, big_height = 0.505;         // m, big orange cone
  double small_top_width = 0.05, big_top_width = 0.06;  // m, the narrow tips
  double width_margin = 0.08;     // m a cluster may exceed a big cone's base (range noise along the line of sight)
  double height_margin = 0.06;    // m a cluster's top may exceed a big cone's
  double profile_margin = 0.04;   // m a slice's half-width may exceed a big cone's radius at its height
  double big_min_height = 0.40;   // m: a cluster reaching this high is a big cone
  double hit_margin = 0.025;      // m inside a cone's top (too flat) or above the ground threshold (floating)
  double beam_spacing_deg = 2.0;  // vertical angle between adjacent lasers (VLP-16: 2°)
  double lowest_beam_deg = -15.0, highest_beam_deg = 15.0;  // the sensor's laser fan (VLP-16: ±15°)
  double azimuth_step_deg = 0.2;                            // horizontal angle between firings (VLP-16 at 10 Hz: 0.2°)
  double min_point_ratio = 0.2;  // share of a small cone's expected points a cluster must have
  int min_points = 2;
  double tall_clearance = 0.7;  // m around a cone free of points higher than a big cone; 0 = off
};
const ConfigSection<ConeSizeConfig>& cone_size_section();  // "perception.lidar.size"

enum class ConeRejection : std::uint8_t {
  None = 0,
  TooSparse,
  TooWide,
  TooTall,
  NotConeShaped,
  TooFlat,
  Floating,
  BesideTaller,
  Black  // by its reflectivity (IntensityColourClassifier::black), not its size
};
const char* to_string(ConeRejection r);

struct ConeMeasurement {
  ConeRejection rejection = ConeRejection::None;
  ConeCandidate candidate;     // filled for every cluster (its measured size), a cone only when rejection is None
  double expected_points = 0;  // what a small cone at that range returns over the accumulated frames
  double visible_share = 1.0;  // of its azimuths, those no nearer return hides (the sparse test's expectation)
};

class ConeSizeFilter {
 public:
  explicit ConeSizeFilter(const ConeSizeConfig& cfg = {}) : cfg_(cfg) {}
  // Measures one cluster of `cloud` (the detector's frame) against the ground plane; `mount` is the sensor's pose
  // in that frame (frame ← sensor), `ground_threshold` the ground stage's τ, `frames` the frames accumulated,
  // `shadow` what nearer returns hide (none: nothing is hidden).
  ConeMeasurement measure(const std::vector<Point>& cloud, const Cluster& cluster, const GroundSurface& ground,
                          const Pose3& mount, double ground_threshold, int frames,
                          const LidarShadow* shadow = nullptr) const;
  // Points a small cone returns at horizontal range r over `frames` frames, where the lasers can cross it between
  // the heights `low` and `high` above the ground (sensor geometry); without limits from τ to its top.
  double expected_points(double range, int frames, double low, double high) const;
  double expected_points(double range, int frames, double ground_threshold) const {
    return expected_points(range, frames, ground_threshold, cfg_.small_height);
  }
  // Whether any of `tall` (x/y of obstacle points higher than a big cone) lies within tall_clearance of `position`.
  bool beside_taller(const Vec3& position, const std::vector<Vec2>& tall) const;
  // Obstacle points of `cloud` higher above the ground than any cone may reach (for beside_taller).
  std::vector<Vec2> tall_points(const std::vector<Point>& cloud, const GroundSurface& ground) const;
  const ConeSizeConfig& config() const { return cfg_; }

 private:
  ConeSizeConfig cfg_;
};

}  // namespace fsd
