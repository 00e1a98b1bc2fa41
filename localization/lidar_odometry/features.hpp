#pragma once
// LOAM's feature selection (Zhang & Singh 2014, §V-A): per ring, the smoothness c of eq. 5 ranks the points; the
// sharpest become edge points, the flattest plane points. Points on the far side of an occlusion and points on a
// surface nearly parallel to the beam are never picked: their neighbourhood moves with the viewpoint, not the world.
#include <vector>

#include "common/types.hpp"
#include "localization/lidar_odometry/config.hpp"

namespace fsd::lidar_odometry {

// A feature point, still in the sensor frame, with its firing time for the deskew.
struct FeaturePoint {
  Vec3 p = Vec3::Zero();
  Stamp t = 0;
  double c = 0;  // smoothness
};

struct Features {
  std::vector<FeaturePoint> edges, planes;
};

class FeatureExtractor {
 public:
  explicit FeatureExtractor(const FeatureConfig& cfg = {}) : cfg_(cfg) {}
  Features extract(const Scan& scan) const;

 private:
  void extract_ring(const std::vector<const Point*>& ring, Features& out) const;
  FeatureConfig cfg_;
};

}  // namespace fsd::lidar_odometry
