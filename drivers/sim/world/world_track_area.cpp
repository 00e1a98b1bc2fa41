#include "drivers/sim/world/world_track_area.hpp"

#include <algorithm>
#include <limits>
#include <set>
#include <utility>

namespace fsd::sim {

Vec2 closest_point_on_segment(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 ab = b - a;
  const double len2 = ab.squaredNorm();
  const double s = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return a + s * ab;
}

TrackArea::TrackArea(const Track& track, double max_gap) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  for (const auto& c : track.cones) cones_.push_back(c.position);
  auto nearest_with_role = [&](const Vec2& p, ConeRole role) {
    double best = kInf;
    for (const auto& c : track.cones)
      if (c.role == role) best = std::min(best, (c.position - p).norm());
    return best;
  };
  for (const auto& c : track.cones) {
    if (c.role == ConeRole::Left)
      sides_.push_back(Side::Left);
    else if (c.role == ConeRole::Right)
      sides_.push_back(Side::Right);
    else
      sides_.push_back(nearest_with_role(c.position, ConeRole::Left) <= nearest_with_role(c.position, ConeRole::Right)
                           ? Side::Left
                           : Side::Right);
  }

  // Boundaries as chains: each cone joins its nearest neighbour of the same role and side and the nearest one on
  // its far side (the half-plane away from the first), within the gap. That follows a boundary even where
  // duplicate cones or a cluster of timing cones are nearer than the next boundary cone. Chain ends then join the
  // nearest cone of any role on their side beyond them, so a line of blue cones continues into the orange ones.
  constexpr double kSamePlace = 0.05;
  std::set<std::pair<std::size_t, std::size_t>> edges;
  std::vector<int> degree(cones_.size(), 0);
  auto nearest = [&](std::size_t i, bool same_role, const Vec2* away_from) {
    std::size_t best = i;
    double best_d = max_gap;
    for (std::size_t j = 0; j < cones_.size(); ++j) {
      if (j == i || sides_[j] != sides_[i] || (same_role && track.cones[j].role != track.cones[i].role)) continue;
      const Vec2 v = cones_[j] - cones_[i];
      const double d = v.norm();
      if (d > kSamePlace && d <= best_d && (!away_from || v.dot(*away_from) < 0.0)) {
        best_d = d;
        best = j;
      }
    }
    return best;
  };
  auto link = [&](std::size_t i, std::size_t j) {
    if (j == i || !edges.insert({std::min(i, j), std::max(i, j)}).second) return;
    ++degree[i];
    ++degree[j];
  };
  std::vector<Vec2> first_dir(cones_.size(), Vec2::Zero());
  for (std::size_t i = 0; i < cones_.size(); ++i) {
    const std::size_t n1 = nearest(i, true, nullptr);
    if (n1 == i) continue;
    first_dir[i] = cones_[n1] - cones_[i];
    link(i, n1);
    link(i, nearest(i, true, &first_dir[i]));
  }
  for (std::size_t i = 0; i < cones_.size(); ++i) {
    if (degree[i] == 1) link(i, nearest(i, false, &first_dir[i]));
    if (degree[i] == 0) {
      const std::size_t n1 = nearest(i, false, nullptr);
      if (n1 == i) {
        edges.insert({i, i});  // isolated cone: a point
        continue;
      }
      const Vec2 toward = cones_[n1] - cones_[i];
      link(i, n1);
      link(i, nearest(i, false, &toward));
    }
  }
  for (const auto& [i, j] : edges) segments_.push_back({cones_[i], cones_[j], sides_[i]});
}

double TrackArea::distance_to_boundary(const Vec2& p) const {
  double best = std::numeric_limits<double>::infinity();
  for (const auto& s : segments_) best = std::min(best, (closest_point_on_segment(p, s.a, s.b) - p).squaredNorm());
  return std::sqrt(best);
}

std::optional<Vec2> TrackArea::nearest_on_side(const Vec2& p, Side side) const {
  std::optional<Vec2> best;
  double best_d2 = std::numeric_limits<double>::infinity();
  for (const auto& s : segments_) {
    if (s.side != side) continue;
    const Vec2 q = closest_point_on_segment(p, s.a, s.b);
    const double d2 = (q - p).squaredNorm();
    if (d2 < best_d2) {
      best_d2 = d2;
      best = q;
    }
  }
  return best;
}

bool TrackArea::on_track(const Vec2& p) const {
  const auto left = nearest_on_side(p, Side::Left);
  const auto right = nearest_on_side(p, Side::Right);
  if (!left || !right) return false;
  // Between the two boundaries, and they are no farther apart than a track is wide (not across an infield).
  return (*left - p).dot(*right - p) < 0.0 && (*left - *right).norm() <= kMaxTrackWidth;
}

std::optional<Vec2> TrackArea::outward_at_cone(std::size_t i) const {
  const Side other = sides_[i] == Side::Left ? Side::Right : Side::Left;
  const auto across = nearest_on_side(cones_[i], other);
  if (!across) return std::nullopt;
  const Vec2 v = cones_[i] - *across;
  if (v.norm() < 1e-6) return std::nullopt;
  return v.normalized();
}

}  // namespace fsd::sim
