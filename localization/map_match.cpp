#include "localization/map_match.hpp"

#include <cmath>

#include "common/cone_pairing.hpp"

namespace fsd {

const ConfigSection<MapMatchConfig>& map_match_section() {
  static const auto s =
      ConfigSection<MapMatchConfig>("localization.map_match")
          .boolean("enabled", &MapMatchConfig::enabled,
                   "Each frame's cones are matched to the cone map and the pose corrected towards it (the map lap 1 "
                   "built and closed, from lap 2 on): run.localization_source = lidar_odometry always, fused while "
                   "no GNSS fix is recent.")
          .number("gate", &MapMatchConfig::gate, 0.05, 5.0, "m",
                  "A detection pairs with the nearest mapped cone this close to where the pose puts it.")
          .number("max_range", &MapMatchConfig::max_range, 1.0, 100.0, "m", "Detections farther away are not used.")
          .integer("min_pairs", &MapMatchConfig::min_pairs, 2, 1000, "", "Fewer pairs: no correction.")
          .number("max_step", &MapMatchConfig::max_step, 0.01, 10.0, "m",
                  "An alignment moving the pose more than this is taken for a wrong pairing and not applied.")
          .number("fused_sigma", &MapMatchConfig::fused_sigma, 0.005, 10.0, "m",
                  "run.localization_source = fused, no GNSS fix recent: a frame's alignment to the cone map is a "
                  "pose measurement of the fusion filter with this position sigma per axis.")
          .number("fused_yaw_sigma", &MapMatchConfig::fused_yaw_sigma, 0.001, 1.0, "rad",
                  "The same measurement's heading sigma.");
  return s;
}

std::optional<MapMatch> match_to_map(const std::vector<Cone>& detections, const Pose2& pose,
                                     const std::vector<Cone>& map, const MapMatchConfig& cfg) {
  if (!cfg.enabled || map.empty()) return std::nullopt;
  // Pairs, nearest first, each detection and each mapped cone at most once (two cones 0.5 m apart stay two), closer
  // than the gate (pair_cones takes it inclusive).
  std::vector<Vec2> seen, mapped;
  for (const auto& d : detections) {
    const Vec2 v = d.position.head<2>();
    if (v.allFinite() && v.norm() <= cfg.max_range) seen.push_back(pose.transform(v));
  }
  mapped.reserve(map.size());
  for (const auto& c : map) mapped.push_back(c.position.head<2>());
  std::vector<std::pair<Vec2, Vec2>> pairs;  // (seen, mapped), map frame
  for (const auto& p : pair_cones(seen, mapped, std::nextafter(cfg.gate, 0.0)))
    pairs.emplace_back(seen[p.estimate], mapped[p.truth]);
  if (static_cast<int>(pairs.size()) < cfg.min_pairs) return std::nullopt;

  // The rigid motion laying the seen points onto the mapped ones (2D Kabsch), about the car's position.
  const Vec2 car = pose.position();
  Vec2 ms = Vec2::Zero(), mm = Vec2::Zero();
  for (const auto& [s, m] : pairs) ms += s - car, mm += m - car;
  ms /= static_cast<double>(pairs.size()), mm /= static_cast<double>(pairs.size());
  double sxx = 0, sxy = 0;  // Σ cross and dot terms of the centred sets
  for (const auto& [s, m] : pairs) {
    const Vec2 a = s - car - ms, b = m - car - mm;
    sxx += a.dot(b);
    sxy += a.x() * b.y() - a.y() * b.x();
  }
  const double yaw = std::atan2(sxy, sxx);
  const Eigen::Rotation2Dd R(yaw);
  const Vec2 t = mm - R * ms;  // about the car: p' = car + R (p - car) + t
  MapMatch out;
  out.pairs = static_cast<int>(pairs.size());
  double before = 0, after = 0;
  for (const auto& [s, m] : pairs) {
    before += (s - m).squaredNorm();
    after += (car + R * (s - car) + t - m).squaredNorm();
  }
  out.rms_before = std::sqrt(before / static_cast<double>(pairs.size()));
  out.rms_after = std::sqrt(after / static_cast<double>(pairs.size()));
  if (t.norm() > cfg.max_step || !(out.rms_after <= out.rms_before)) return std::nullopt;
  // As a map ← estimated correction: rotate about the car, then shift.
  out.alignment = share_of_correction(car, yaw, t, 1.0);
  return out;
}

}  // namespace fsd
