#include "perception/truth_perception.hpp"

#include <cmath>

namespace fsd {

const ConfigSection<TruthPerceptionConfig>& truth_perception_section() {
  static const auto s =
      ConfigSection<TruthPerceptionConfig>("run.truth_perception")
          .number("range", &TruthPerceptionConfig::range, 1.0, 100.0, "m", "Range of the ideal cone detector.")
          .number("fov_deg", &TruthPerceptionConfig::fov_deg, 10.0, 360.0, "deg", "Its horizontal field of view.")
          .number("position_noise", &TruthPerceptionConfig::position_noise, 0.0, 1.0, "m",
                  "σ of the position noise per axis.")
          .number("min_range", &TruthPerceptionConfig::min_range, 0.0, 10.0, "m", "Cones closer are not seen.");
  return s;
}

ConeDetections TruthPerception::detect(Stamp t, const std::vector<Cone>& cones, const Pose2& pose) {
  ConeDetections out;
  out.stamp = t;
  std::normal_distribution<double> noise(0.0, cfg_.position_noise);
  const double half_fov = 0.5 * cfg_.fov_deg * std::numbers::pi / 180.0;
  for (const auto& c : cones) {
    const Vec2 local = pose.inverse_transform(c.position.head<2>());
    const double r = local.norm();
    if (r > cfg_.range || r < cfg_.min_range) continue;
    if (std::fabs(std::atan2(local.y(), local.x())) > half_fov) continue;
    Cone d = c;
    d.position = Vec3(local.x() + noise(rng_), local.y() + noise(rng_), 0.0);
    const double var = std::max(cfg_.position_noise * cfg_.position_noise, 1e-4);
    d.covariance = Eigen::Matrix2d::Identity() * var;
    d.id = 0;
    out.cones.push_back(d);
  }
  return out;
}

}  // namespace fsd
