#include "localization/cone_map.hpp"

#include <algorithm>
#include <limits>

namespace fsd {

const ConfigSection<ConeMapConfig>& cone_map_section() {
  static const auto s = ConfigSection<ConeMapConfig>("localization.cone_map")
                            .number("association_gate", &ConeMapConfig::association_gate, 0.1, 5.0, "m",
                                    "A detection this close to a mapped cone is the same cone.")
                            .number("colour_conflict_gate", &ConeMapConfig::colour_conflict_gate, 0.05, 5.0, "m",
                                    "A detection of another colour than the mapped cone's is that cone only this close.")
                            .integer("min_observations", &ConeMapConfig::min_observations, 1, 100, "",
                                     "Observations before a cone is reported (rejects one-off ghosts).")
                            .number("max_range", &ConeMapConfig::max_range, 1.0, 100.0, "m",
                                    "Detections beyond this range are not mapped.");
  return s;
}

namespace {

ConeColour voted_colour(const std::array<int, 6>& votes) {
  const auto top = std::max_element(votes.begin(), votes.end());
  return *top > 0 ? static_cast<ConeColour>(top - votes.begin()) : ConeColour::Unknown;
}

}  // namespace

void ConeMap::update(const ConeDetections& detections, const Pose2& pose) {
  const Eigen::Matrix2d R = pose.rotation().toRotationMatrix();
  for (const auto& d : detections.cones) {
    const Vec2 local = d.position.head<2>();
    if (local.norm() > cfg_.max_range) continue;
    const Vec2 p = pose.transform(local);
    // Covariance rotated into the map frame; floor it so a zero covariance cannot make the information infinite.
    Eigen::Matrix2d cov = R * d.covariance * R.transpose();
    cov += Eigen::Matrix2d::Identity() * 1e-4;
    const Eigen::Matrix2d info = cov.inverse();

    Entry* best = nullptr;
    double best_d = cfg_.association_gate;
    for (auto& e : entries_) {
      const double dist = (e.mean - p).norm();
      if (dist >= best_d) continue;
      const ConeColour mapped = voted_colour(e.colour_votes);
      const bool conflict = d.colour != ConeColour::Unknown && mapped != ConeColour::Unknown && mapped != d.colour;
      if (conflict && dist >= cfg_.colour_conflict_gate) continue;
      best_d = dist, best = &e;
    }
    if (!best) {
      best = &entries_.emplace_back();
      best->id = next_id_++;
    }
    best->info += info;
    best->info_vec += info * p;
    best->mean = best->info.ldlt().solve(best->info_vec);
    ++best->observations;
    const auto c = static_cast<std::size_t>(d.colour);
    if (d.colour != ConeColour::Unknown && c < best->colour_votes.size()) ++best->colour_votes[c];
  }
}

std::vector<Cone> ConeMap::cones() const {
  std::vector<Cone> out;
  for (const auto& e : entries_) {
    if (e.observations < cfg_.min_observations) continue;
    Cone c;
    c.position = Vec3(e.mean.x(), e.mean.y(), 0.0);
    c.covariance = e.info.inverse();
    c.id = e.id;
    int total = 0;
    for (int v : e.colour_votes) total += v;
    c.colour = voted_colour(e.colour_votes);
    const int top = *std::max_element(e.colour_votes.begin(), e.colour_votes.end());
    c.confidence = total > 0 ? static_cast<double>(top) / total : 0.0;
    out.push_back(c);
  }
  return out;
}

}  // namespace fsd
