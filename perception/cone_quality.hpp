#pragma once
// How much to trust a LiDAR cone detection: a range-dependent confidence and position covariance, for the cone
// map's information-form fusion and for a planner that weighs near cones more.
//
// Confidence: the cluster's support (its points against what a small cone returns at that range, at most 1)
// times a range factor falling linearly from 1 at the sensor to `far_confidence` at `confidence_range`.
// Covariance: along the line of sight σ_r = sigma_base + sigma_radial_per_m · r (range noise, the depth model);
// across it σ_t = sigma_base + sigma_tangential_per_m · r (the azimuth step: a silhouette edge is known to one
// firing, 0.0035 · r at 10 Hz).
#include "common/config.hpp"
#include "common/geometry.hpp"

namespace fsd {

struct ConeQualityConfig {
  double confidence_range = 25.0;  // m where the range factor reaches far_confidence
  double far_confidence = 0.3;
  double sigma_base = 0.02;           // m
  double sigma_radial_per_m = 0.003;  // m per m of range
  double sigma_tangential_per_m = 0.002;
};
const ConfigSection<ConeQualityConfig>& cone_quality_section();  // "perception.lidar.quality"

double cone_confidence(const ConeQualityConfig& cfg, double range, double points, double expected_points);
// Covariance in the frame of the detection, for a cone at `position` seen from `sensor` (both x/y).
Eigen::Matrix2d cone_covariance(const ConeQualityConfig& cfg, const Vec2& position, const Vec2& sensor);

}  // namespace fsd
