#include "perception/cone_quality.hpp"

#include <algorithm>

namespace fsd {

const ConfigSection<ConeQualityConfig>& cone_quality_section() {
  static const auto s =
      ConfigSection<ConeQualityConfig>("perception.lidar.quality")
          .number("confidence_range", &ConeQualityConfig::confidence_range, 1.0, 200.0, "m",
                  "Range where a detection's confidence factor has fallen to far_confidence.")
          .number("far_confidence", &ConeQualityConfig::far_confidence, 0.0, 1.0, "",
                  "Confidence factor at confidence_range and beyond.")
          .number("sigma_base", &ConeQualityConfig::sigma_base, 0.001, 1.0, "m",
                  "Position standard deviation of a detection at the sensor.")
          .number("sigma_radial_per_m", &ConeQualityConfig::sigma_radial_per_m, 0.0, 0.1, "m/m",
                  "Growth of the standard deviation along the line of sight per metre of range.")
          .number("sigma_tangential_per_m", &ConeQualityConfig::sigma_tangential_per_m, 0.0, 0.1, "m/m",
                  "Growth of the standard deviation across the line of sight per metre of range.");
  return s;
}

double cone_confidence(const ConeQualityConfig& cfg, double range, double points, double expected_points) {
  const double support = expected_points > 0 ? std::min(1.0, points / expected_points) : 1.0;
  const double f = std::clamp(range / cfg.confidence_range, 0.0, 1.0);
  return support * (1.0 - f * (1.0 - cfg.far_confidence));
}

Eigen::Matrix2d cone_covariance(const ConeQualityConfig& cfg, const Vec2& position, const Vec2& sensor) {
  Vec2 los = position - sensor;
  const double r = los.norm();
  los = r > 1e-6 ? Vec2(los / r) : Vec2(1.0, 0.0);
  const double sr = cfg.sigma_base + cfg.sigma_radial_per_m * r;
  const double st = cfg.sigma_base + cfg.sigma_tangential_per_m * r;
  Eigen::Matrix2d R;
  R.col(0) = los;
  R.col(1) = Vec2(-los.y(), los.x());
  return R * Eigen::Vector2d(sr * sr, st * st).asDiagonal() * R.transpose();
}

}  // namespace fsd
