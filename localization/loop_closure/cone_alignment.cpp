#include "localization/loop_closure/cone_alignment.hpp"

#include <algorithm>
#include <cmath>

namespace fsd::loop_closure {

namespace {

bool compatible(ConeColour a, ConeColour b) { return a == b || a == ConeColour::Unknown || b == ConeColour::Unknown; }

Vec2 xy(const Cone& c) { return c.position.head<2>(); }

struct Hypothesis {
  Pose2 t;
  int pairs = 0;
};

// One-to-one pairs under `t`, nearest first, within the tolerance.
std::vector<std::pair<int, int>> pairs_under(const Pose2& t, const std::vector<Cone>& cur, const std::vector<Cone>& ref,
                                             const std::vector<std::vector<int>>& candidates, double tol) {
  struct Near {
    double d;
    int i, j;
  };
  std::vector<Near> all;
  for (std::size_t i = 0; i < cur.size(); ++i) {
    const Vec2 p = t.transform(xy(cur[i]));
    for (int j : candidates[i]) {
      const double d = (p - xy(ref[std::size_t(j)])).norm();
      if (d <= tol) all.push_back({d, int(i), j});
    }
  }
  std::sort(all.begin(), all.end(), [](const Near& a, const Near& b) { return a.d < b.d; });
  std::vector<char> used_i(cur.size(), 0), used_j(ref.size(), 0);
  std::vector<std::pair<int, int>> out;
  for (const auto& n : all) {
    if (used_i[std::size_t(n.i)] || used_j[std::size_t(n.j)]) continue;
    used_i[std::size_t(n.i)] = used_j[std::size_t(n.j)] = 1;
    out.emplace_back(n.i, n.j);
  }
  return out;
}

// The least-squares rigid transform (2-D Kabsch) taking the current cones of `pairs` onto their references.
Pose2 fit(const std::vector<std::pair<int, int>>& pairs, const std::vector<Cone>& cur, const std::vector<Cone>& ref) {
  Vec2 mc = Vec2::Zero(), mr = Vec2::Zero();
  for (const auto& [i, j] : pairs) mc += xy(cur[std::size_t(i)]), mr += xy(ref[std::size_t(j)]);
  mc /= double(pairs.size());
  mr /= double(pairs.size());
  double sxx = 0, sxy = 0;  // Σ a·b and Σ a×b of the centred pairs
  for (const auto& [i, j] : pairs) {
    const Vec2 a = xy(cur[std::size_t(i)]) - mc, b = xy(ref[std::size_t(j)]) - mr;
    sxx += a.dot(b);
    sxy += a.x() * b.y() - a.y() * b.x();
  }
  const double yaw = std::atan2(sxy, sxx);
  const Vec2 t = mr - Eigen::Rotation2Dd(yaw) * mc;
  return {t.x(), t.y(), yaw};
}

// Current cones that land within `radius` of a reference cone (any colour) under `t` without pairing, but for
// copies: a cone mapped twice in the lap (its sightings split by a jump of the pose) lands by the reference its
// other copy paired with, and says nothing against `t`. A copy is within `copy_radius` of a paired current cone of
// a compatible colour; a start line's big orange cone landing by a blue one is no copy of it.
int landed_unpaired(const Pose2& t, const std::vector<Cone>& cur, const std::vector<Cone>& ref,
                    const std::vector<std::vector<int>>& near_any, const std::vector<std::pair<int, int>>& pairs,
                    double radius, double copy_radius) {
  std::vector<char> paired(cur.size(), 0);
  for (const auto& [i, j] : pairs) paired[std::size_t(i)] = 1;
  int n = 0;
  for (std::size_t i = 0; i < cur.size(); ++i) {
    if (paired[i]) continue;
    const Vec2 p = t.transform(xy(cur[i]));
    const bool lands = std::any_of(near_any[i].begin(), near_any[i].end(),
                                   [&](int j) { return (p - xy(ref[std::size_t(j)])).norm() <= radius; });
    if (!lands) continue;
    const bool copy = std::any_of(pairs.begin(), pairs.end(), [&](const std::pair<int, int>& pr) {
      const Cone& k = cur[std::size_t(pr.first)];
      return compatible(k.colour, cur[i].colour) && (xy(k) - xy(cur[i])).norm() <= copy_radius;
    });
    n += !copy;
  }
  return n;
}

}  // namespace

std::optional<ConeAlignment> align_cones(const std::vector<Cone>& current, const std::vector<Cone>& reference,
                                         const ConeAlignmentConfig& cfg) {
  if (int(current.size()) < cfg.min_pairs || int(reference.size()) < cfg.min_pairs) return std::nullopt;
  std::vector<std::vector<int>> candidates(current.size()), near_any(current.size());
  for (std::size_t i = 0; i < current.size(); ++i)
    for (std::size_t j = 0; j < reference.size(); ++j) {
      const double d = (xy(current[i]) - xy(reference[j])).norm();
      if (d <= cfg.max_drift + cfg.landing_radius) near_any[i].push_back(int(j));
      if (compatible(current[i].colour, reference[j].colour) && d <= cfg.max_drift + cfg.pair_tolerance)
        candidates[i].push_back(int(j));
    }

  std::vector<Hypothesis> hyps;
  const double tol = cfg.pair_tolerance;
  for (std::size_t i1 = 0; i1 < current.size(); ++i1) {
    for (std::size_t i2 = i1 + 1; i2 < current.size(); ++i2) {
      const Vec2 a1 = xy(current[i1]), a2 = xy(current[i2]);
      const double d = (a2 - a1).norm();
      if (d < 1.0) continue;  // too close to fix a rotation
      for (int j1 : candidates[i1]) {
        for (int j2 : candidates[i2]) {
          if (j1 == j2) continue;
          const Vec2 b1 = xy(reference[std::size_t(j1)]), b2 = xy(reference[std::size_t(j2)]);
          if (std::abs((b2 - b1).norm() - d) > tol) continue;
          const double yaw =
              wrap_angle(std::atan2((b2 - b1).y(), (b2 - b1).x()) - std::atan2((a2 - a1).y(), (a2 - a1).x()));
          if (std::abs(yaw) > cfg.max_rotation) continue;
          const Vec2 t = 0.5 * (b1 + b2) - Eigen::Rotation2Dd(yaw) * (0.5 * (a1 + a2));
          const Pose2 h{t.x(), t.y(), yaw};
          hyps.push_back({h, int(pairs_under(h, current, reference, candidates, tol).size())});
        }
      }
    }
  }
  if (hyps.empty()) return std::nullopt;
  auto consistent = [&](const Hypothesis& h) {
    const auto pairs = pairs_under(h.t, current, reference, candidates, tol);
    return landed_unpaired(h.t, current, reference, near_any, pairs, cfg.landing_radius, cfg.copy_radius) <=
           cfg.max_unpaired;
  };
  // Most pairs first: the first consistent one is the answer.
  std::stable_sort(hyps.begin(), hyps.end(),
                   [](const Hypothesis& a, const Hypothesis& b) { return a.pairs > b.pairs; });
  const auto best = std::find_if(hyps.begin(), hyps.end(), consistent);
  if (best == hyps.end() || best->pairs < cfg.min_pairs) return std::nullopt;
  // A consistent rival elsewhere: the scene does not say which (a lane slid along itself).
  Vec2 centre = Vec2::Zero();
  for (const auto& c : current) centre += xy(c);
  centre /= double(current.size());
  const Vec2 at_best = best->t.transform(centre);
  for (auto h = best + 1; h != hyps.end() && h->pairs >= cfg.rival_min_pairs; ++h)
    if ((h->t.transform(centre) - at_best).norm() > 2 * tol && consistent(*h)) return std::nullopt;

  ConeAlignment out;
  out.pairs = pairs_under(best->t, current, reference, candidates, tol);
  out.correction = fit(out.pairs, current, reference);
  // The fitted transform may gather a pair or two more (or lose one at the edge): pair again, fit again.
  out.pairs = pairs_under(out.correction, current, reference, candidates, tol);
  if (int(out.pairs.size()) < cfg.min_pairs) return std::nullopt;
  out.correction = fit(out.pairs, current, reference);
  double ss = 0;
  for (const auto& [i, j] : out.pairs)
    ss += (out.correction.transform(xy(current[std::size_t(i)])) - xy(reference[std::size_t(j)])).squaredNorm();
  out.rms = std::sqrt(ss / double(out.pairs.size()));
  return out;
}

}  // namespace fsd::loop_closure
