#include "daemon/map_score.hpp"

#include <algorithm>
#include <cmath>
#include <tuple>

#include <nlohmann/json.hpp>

namespace fsd {

MapScore score_map(const std::vector<TrackCone>& truth, const std::vector<Cone>& mapped, double gate) {
  MapScore s;
  s.true_cones = static_cast<int>(truth.size());
  s.mapped = static_cast<int>(mapped.size());
  // Every candidate pair within the gate, nearest first; a pair is taken while both of its cones are free.
  std::vector<std::tuple<double, std::size_t, std::size_t>> pairs;
  for (std::size_t m = 0; m < mapped.size(); ++m) {
    const Vec2 p = mapped[m].position.head<2>();
    if (!p.allFinite()) continue;
    for (std::size_t t = 0; t < truth.size(); ++t) {
      const double d = (truth[t].position - p).norm();
      if (d <= gate) pairs.emplace_back(d, m, t);
    }
  }
  std::sort(pairs.begin(), pairs.end());
  std::vector<bool> map_used(mapped.size(), false), truth_used(truth.size(), false);
  double sq = 0;
  int right_colour = 0;
  for (const auto& [d, m, t] : pairs) {
    if (map_used[m] || truth_used[t]) continue;
    map_used[m] = truth_used[t] = true;
    ++s.matched;
    sq += d * d;
    if (mapped[m].colour == truth[t].colour) ++right_colour;
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
  return {{"true_cones", s.true_cones}, {"mapped", s.mapped},   {"matched", s.matched},
          {"missed", s.missed},         {"ghosts", s.ghosts},   {"rmse_m", s.rmse_m},
          {"colour_accuracy", s.colour_accuracy}};
}

}  // namespace fsd
