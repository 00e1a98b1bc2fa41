#include "daemon/scoring/map_score.hpp"

#include <cmath>

#include <nlohmann/json.hpp>

#include "common/cone_pairing.hpp"

namespace fsd {

MapScore score_map(const std::vector<TrackCone>& truth, const std::vector<Cone>& mapped, double gate) {
  MapScore s;
  s.true_cones = static_cast<int>(truth.size());
  s.mapped = static_cast<int>(mapped.size());
  std::vector<Vec2> est, tru;
  for (const auto& m : mapped) est.push_back(m.position.head<2>());
  for (const auto& t : truth) tru.push_back(t.position);
  double sq = 0;
  int right_colour = 0;
  for (const auto& p : pair_cones(est, tru, gate)) {
    ++s.matched;
    sq += p.distance * p.distance;
    if (mapped[p.estimate].colour == truth[p.truth].colour) ++right_colour;
  }
  s.missed = s.true_cones - s.matched;
  s.ghosts = s.mapped - s.matched;
  if (s.matched > 0) {
    s.rmse_m = std::sqrt(sq / s.matched);
    s.colour_accuracy = static_cast<double>(right_colour) / s.matched;
  }
  return s;
}

nlohmann::json to_json(const MapScore& s) {
  return {{"true_cones", s.true_cones},
          {"mapped", s.mapped},
          {"matched", s.matched},
          {"missed", s.missed},
          {"ghosts", s.ghosts},
          {"rmse_m", std::round(s.rmse_m * 1e4) / 1e4},
          {"colour_accuracy", std::round(s.colour_accuracy * 1e4) / 1e4}};
}

}  // namespace fsd
