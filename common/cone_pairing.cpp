#include "common/cone_pairing.hpp"

#include <algorithm>

namespace fsd {

std::vector<ConePair> pair_cones(const std::vector<Vec2>& estimates, const std::vector<Vec2>& truths, double gate) {
  std::vector<ConePair> candidates;
  for (std::size_t e = 0; e < estimates.size(); ++e) {
    if (!estimates[e].allFinite()) continue;
    for (std::size_t t = 0; t < truths.size(); ++t) {
      const double d = (truths[t] - estimates[e]).norm();
      if (d <= gate) candidates.push_back({e, t, d});
    }
  }
  std::sort(candidates.begin(), candidates.end(), [](const ConePair& a, const ConePair& b) {
    return a.distance < b.distance ||
           (a.distance == b.distance && (a.estimate < b.estimate || (a.estimate == b.estimate && a.truth < b.truth)));
  });
  std::vector<bool> e_used(estimates.size(), false), t_used(truths.size(), false);
  std::vector<ConePair> pairs;
  for (const auto& c : candidates) {
    if (e_used[c.estimate] || t_used[c.truth]) continue;
    e_used[c.estimate] = t_used[c.truth] = true;
    pairs.push_back(c);
  }
  return pairs;
}

}  // namespace fsd
