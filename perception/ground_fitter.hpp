#pragma once
// Stage 2, ground (paper §III.A.1): a plane fitted by RANSAC with its tilt (pitch/roll) and height constrained
// around the mount, inlier threshold τ; the inliers are the ground and are removed.
//
// Two methods, chosen by `method`:
//  - "grid_lsq" (default): RANSAC on the lowest point of each cell of a horizontal grid (a few hundred seeds
//    instead of the whole cloud: obstacles rarely hold the lowest point of a cell), then least squares on every
//    point within τ of the best plane, twice. Faster than RANSAC on the whole cloud and not biased by the
//    threshold band the way a pure RANSAC plane is.
//  - "pcl_sac": the paper's reference, PCL SACSegmentation with SACMODEL_PERPENDICULAR_PLANE (normal within
//    max_tilt of z) on the whole cropped cloud; the height bound is checked afterwards.
// Both are deterministic (fixed seeds).
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "common/config.hpp"
#include "common/types.hpp"
#include "perception/ground_plane.hpp"

namespace fsd {

struct GroundConfig {
  std::string method = "grid_lsq";   // "grid_lsq" | "pcl_sac"
  double distance_threshold = 0.05;  // τ, m: points nearer to the plane are ground
  double max_tilt_deg = 8.0;         // the plane's normal is within this of the frame's z axis
  // Bounds of h, the plane's height at the frame origin: around 0 in the vehicle frame (origin on the ground);
  // `fsd detect` widens them to anything below the sensor.
  double height_min = -0.3, height_max = 0.3;
  int iterations = 100;    // RANSAC hypotheses
  double seed_cell = 1.0;  // m, grid cell of the "grid_lsq" seeds
  int min_inliers = 30;    // fewer inliers: no plane found
  // Grazing beams (ground_split.hpp): where the ±τ band is longer than grazing_band along a laser, a band point
  // grazing_drop (share of the range) short of its laser's neighbours within ±grazing_window_deg is an obstacle.
  double grazing_band = 0.5;  // m; 0 = off
  double grazing_drop = 0.04;
  double grazing_window_deg = 4.0;
  double grazing_margin = 3.0;  // m beyond the region of interest whose points serve as neighbours
  // The plane is fitted to the points within fit_radius of the frame origin (the ground nearest the car, where a
  // plane holds best); beyond, the local corrections (ground_surface.hpp) follow the ground.
  double fit_radius = 15.0;  // m
  double local_cell = 4.0;   // m; 0 = the plane alone
  double local_band = 0.25;  // m
  int local_min_points = 10;
  double local_min_extent = 1.0;  // m
  double local_min_fill = 0.5;    // share of one ring's returns over the layer's spread (LocalGroundConfig)
};
const ConfigSection<GroundConfig>& ground_section();  // "perception.lidar.ground"

class GroundFitter {
 public:
  explicit GroundFitter(const GroundConfig& cfg = {});
  // Fits the plane to `points` (the detector's frame). Invalid when no plane within the bounds has enough inliers.
  GroundPlane fit(const std::vector<Point>& points);
  const GroundConfig& config() const { return cfg_; }

 private:
  GroundPlane fit_grid_lsq(const std::vector<Point>& points);
  GroundPlane fit_pcl_sac(const std::vector<Point>& points) const;
  bool admissible(double a, double b, double h) const;
  GroundConfig cfg_;
  double max_slope_;  // tan(max tilt)
  std::mt19937 rng_;
  std::vector<int> cell_lowest_;  // per grid cell: index of its lowest point, -1 when empty
  std::vector<Eigen::Vector3f> seeds_;
  std::vector<Point> near_;  // the points within fit_radius
};

// Least-squares plane z = a·x + b·y + h through the points within `threshold` (signed distance) of `plane`,
// measured over `points`; the plane's inlier count and RMS are set. Returns an invalid plane on a degenerate set.
GroundPlane refit_plane(const std::vector<Point>& points, const GroundPlane& plane, double threshold);
// Sets the plane's inlier count and RMS over the points within `threshold` of it.
void score_plane(const std::vector<Point>& points, double threshold, GroundPlane& plane);

}  // namespace fsd
