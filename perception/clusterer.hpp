#pragma once
// Stage 4, Euclidean clustering (paper §III.A.3): points closer than a tolerance belong to the same object.
//
// The distance is measured in the ground plane plus `z_weight` times the height difference: cones stand on the
// ground, so their points lie within the base's footprint however far apart the laser rings hit them (0.35 m
// between rings at 10 m), while two cones never share a footprint (≥ 0.5 m between centres on the shared tracks).
// Two methods, chosen by `method`:
//  - "grid" (default): a hash grid of cells one tolerance wide and union-find over the neighbouring cells, with a
//    range-aware tolerance max(tolerance, range_factor · range from the sensor), so that the sparse returns of a
//    far object (one azimuth step is 0.0035·range at 10 Hz) stay one cluster.
//  - "pcl_euclidean": the paper's reference, PCL EuclideanClusterExtraction (kd-tree, fixed tolerance).
#include <cstdint>
#include <string>
#include <vector>

#include "common/config.hpp"
#include "common/types.hpp"

namespace fsd {

struct ClusterConfig {
  std::string method = "grid";  // "grid" | "pcl_euclidean"
  double tolerance = 0.2;       // m: under the 0.24 m between the bases of two cones 0.5 m apart
  double range_factor = 0.01;   // m per m of range (grid only): ~3 azimuth steps of the VLP-16 at 10 Hz
  double z_weight = 0.0;        // weight of the height difference in the distance (0: footprint only)
  int min_points = 2;
  int max_points = 5000;
};
const ConfigSection<ClusterConfig>& cluster_section();  // "perception.lidar.cluster"

struct Cluster {
  std::vector<std::uint32_t> indices;  // into the clustered cloud
};

class Clusterer {
 public:
  explicit Clusterer(const ClusterConfig& cfg = {}) : cfg_(cfg) {}
  // Clusters `points`; `sensor_xy` is the sensor's position in their frame (for the range-aware tolerance).
  // Clusters with fewer than min_points or more than max_points are dropped; `too_large` counts the latter.
  std::vector<Cluster> cluster(const std::vector<Point>& points, const Vec2& sensor_xy,
                               std::size_t* too_large = nullptr);
  const ClusterConfig& config() const { return cfg_; }

 private:
  std::vector<Cluster> cluster_grid(const std::vector<Point>& points, const Vec2& sensor_xy);
  std::vector<Cluster> cluster_pcl(const std::vector<Point>& points) const;
  ClusterConfig cfg_;
  // Reused between frames.
  std::vector<std::uint32_t> cell_start_, order_, parent_;
  std::vector<std::uint32_t> cell_of_;
  std::vector<float> tol_;
};

}  // namespace fsd
