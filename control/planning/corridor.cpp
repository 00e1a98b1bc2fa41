#include "control/planning/corridor.hpp"

#include <algorithm>
#include <array>
#include <limits>

namespace fsd {

Corridor corridor_along(const Path& path, const std::vector<Cone>& cones, const ColourConvention& convention,
                        double reach) {
  Corridor c;
  struct Unnamed {
    double s, lateral;
    Vec2 p;
  };
  std::vector<Unnamed> unnamed;  // cones without a side's colour: placed once the named ones are
  // The named cones' distance from the path on each side, by arc length: what the boundary is near an unnamed cone.
  std::vector<std::pair<double, double>> named_left, named_right;
  for (const auto& cone : cones) {
    if (!cone.position.allFinite()) continue;
    const auto foot = project(path, cone.position.head<2>());
    if (!foot || foot->distance() > reach) continue;
    const ConeRole role = convention.role_of(cone.colour);
    const Vec2 p = cone.position.head<2>();
    if (role == ConeRole::Left) {
      c.left.push_back({foot->s, p});
      named_left.emplace_back(foot->s, std::abs(foot->lateral));
    } else if (role == ConeRole::Right) {
      c.right.push_back({foot->s, p});
      named_right.emplace_back(foot->s, std::abs(foot->lateral));
    } else {
      unnamed.push_back({foot->s, foot->lateral, p});
    }
  }
  // A cone without a colour is on the side of the path it stands, unless it stands farther out than that side's
  // named cones nearby: outside the boundary it bounds nothing (a tyre, a post, a fence the LiDAR took for a cone,
  // which would bend the boundary out and the centre line with it). Inside, or where no named cone is near, it
  // counts: a narrower corridor is the safe side.
  constexpr double kOutside = 0.5;  // m beyond the farthest named cone nearby
  const double window = kMaxSpanInReach * reach;
  for (const auto& u : unnamed) {
    const bool left = u.lateral > 0;
    double farthest = -1;
    for (const auto& [s, lateral] : left ? named_left : named_right)
      if (std::abs(s_difference(path, u.s, s)) <= window) farthest = std::max(farthest, lateral);
    if (farthest >= 0 && std::abs(u.lateral) > farthest + kOutside) continue;
    (left ? c.left : c.right).push_back({u.s, u.p});
  }
  auto by_s = [](const BoundaryCone& a, const BoundaryCone& b) { return a.s < b.s; };
  std::sort(c.left.begin(), c.left.end(), by_s);
  std::sort(c.right.begin(), c.right.end(), by_s);
  return c;
}

std::optional<Vec2> closest_on_boundary(const std::vector<BoundaryCone>& b, const Path& path, double s, const Vec2& p,
                                        double window) {
  if (b.size() < 2) return std::nullopt;
  std::optional<Vec2> best;
  double best_d = std::numeric_limits<double>::infinity();
  const std::size_t n = path.closed ? b.size() : b.size() - 1;
  auto consider = [&](std::size_t i) {
    if (i >= n) return;
    const BoundaryCone& u = b[i];
    const BoundaryCone& v = b[(i + 1) % b.size()];
    if (s_difference(path, s, u.s) > window || s_difference(path, v.s, s) > window) return;
    const double span = s_difference(path, u.s, v.s);
    if (span < 0 || span > kMaxSpanInReach * window) return;  // a gap, or a jump over half the lap
    const Vec2 d = v.p - u.p;
    const double l2 = d.squaredNorm();
    const double t = l2 > 0 ? std::clamp((p - u.p).dot(d) / l2, 0.0, 1.0) : 0.0;
    const Vec2 q = u.p + t * d;
    if ((q - p).norm() < best_d) best_d = (q - p).norm(), best = q;
  };
  // Only segments starting within [s − (1 + kMaxSpanInReach)·window, s + window] along the path can pass the
  // tests above: found by bisection in b (sorted by s), once per turn of a closed lap that the window may wrap to.
  const double lo = s - (1.0 + kMaxSpanInReach) * window, hi = s + window;
  const double L = path.closed ? path.length() : 0.0;
  auto by_s = [](const BoundaryCone& c, double x) { return c.s < x; };
  const std::array<double, 3> shifts{-L, 0.0, L};
  for (std::size_t k = path.closed ? 0 : 1; k < (path.closed ? 3 : 2); ++k) {
    const double shift = shifts[k];
    auto it = std::lower_bound(b.begin(), b.end(), lo + shift, by_s);
    for (; it != b.end() && it->s <= hi + shift; ++it) consider(static_cast<std::size_t>(it - b.begin()));
  }
  return best;
}

}  // namespace fsd
