#pragma once
// Stage 4b, beyond the paper: a cluster too wide for one cone split into the cones touching in it.
//
// Cones placed by hand in a tight turn can stand a few centimetres apart at the base (closer than the clustering
// tolerance), so their points form one cluster that the size filter rejects as too wide. A cone narrows towards
// its tip (small cone: 114 mm radius at the base, 81 mm at 0.12 m), so the points above `tip_height` of touching
// cones fall apart into one group per cone even where the bases touch, while a box, a kerb, a tyre or a fence
// panel keeps one continuous top. The split: group the high points (range-aware tolerance, as the clusterer's; and
// consecutive firings of one laser whose returns lie within `reach` are one top: between two tips side by side a
// laser passes through air for a firing or more, and from a tip to one behind it its range jumps);
// with two or more groups standing at least `min_separation` apart, give every point of the cluster to the nearest
// group's axis within a big cone's base radius. The cluster is split only when those parts hold (nearly) all of its
// points: a cluster that is cones and something else stays one, and rejected. Each part must also show it is a
// cone: returns over `min_height_span` of height (the narrowing), or, from one laser, a return brighter than black
// rubber (the returns of a black tyre thin out into pieces along one laser's arc; a cone's paint reflects). The
// caller measures every part with the size filter and keeps them only if each part is a cone by itself.
#include <vector>

#include "common/config.hpp"
#include "common/types.hpp"
#include "perception/clusterer.hpp"
#include "perception/ground_surface.hpp"

namespace fsd {

struct TouchingConesConfig {
  bool enabled = true;
  double tip_height = 0.12;       // m above the ground: points higher than this are a cone's upper part
  double tip_tolerance = 0.06;    // m between the upper points of one cone (grows with range: azimuth steps)
  double min_height_span = 0.03;  // m of height a part's returns span (else: one laser, and paint must show)
  double min_separation = 0.15;   // m between two upper parts' centres (two cones' axes are ≥ 0.23 m apart)
  double reach = 0.18;            // m from a part's axis a point may lie (a big cone's base radius + range noise)
  double max_width = 3.0;         // m: a wider cluster is not a row of touching cones (a wall, a fence, a car)
  double min_explained = 0.95;    // share of the cluster's points the parts must hold
  int min_tip_points = 2;         // upper points a part needs
};
const ConfigSection<TouchingConesConfig>& touching_cones_section();  // "perception.lidar.touching"

class TouchingConesSplitter {
 public:
  // `azimuth_step_deg`: the sensor's horizontal step (the upper points' spacing grows with range); `dark_max`: the
  // calibrated reflectivity of black rubber (IntensityColourConfig::black_max), negative when the intensities have
  // no known scale (then only the shape counts).
  explicit TouchingConesSplitter(const TouchingConesConfig& cfg = {}, double azimuth_step_deg = 0.2,
                                 double dark_max = -1.0);
  // The parts of `cluster` (indices into `cloud`, in the ground frame of `ground`), one per touching cone; empty
  // when the cluster does not split into two or more cones' shapes. `sensor_xy`: the sensor in the cloud's frame.
  std::vector<Cluster> split(const std::vector<Point>& cloud, const Cluster& cluster, const GroundSurface& ground,
                             const Vec2& sensor_xy);
  const TouchingConesConfig& config() const { return cfg_; }

 private:
  // The groups of upper points (indices into high_) with those holding consecutive firings of one laser joined.
  std::vector<Cluster> join_continuous(std::vector<Cluster> groups) const;

  TouchingConesConfig cfg_;
  double dark_max_;
  double azimuth_step_;  // rad
  Clusterer tips_;
  std::vector<Point> high_;
};

}  // namespace fsd
