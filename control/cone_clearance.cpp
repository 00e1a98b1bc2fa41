#include "control/cone_clearance.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace fsd {
namespace {

struct TooNear {
  PathProjection foot;
  double shortfall;  // m: need − distance
};

// The cones nearer the path than `need`, with where they stand beside it.
std::vector<TooNear> too_near(const Path& path, const std::vector<Vec2>& cones, double need) {
  std::vector<TooNear> out;
  for (const auto& c : cones)
    if (const auto f = project(path, c); f && f->distance() < need) out.push_back({*f, need - f->distance()});
  return out;
}

double worst(const std::vector<TooNear>& near) {
  double w = 0;
  for (const auto& n : near) w = std::max(w, n.shortfall);
  return w;
}

}  // namespace

ConeClearance keep_clear_of_cones(Path& path, const std::vector<Vec2>& cones, double need, double window,
                                  double keep_start) {
  ConeClearance r;
  auto& pts = path.points;
  if (path.closed || pts.size() < 4 || window <= 0) return r;
  auto near = too_near(path, cones, need);
  r.cones_too_near = static_cast<int>(near.size());
  r.worst_before = r.worst_after = worst(near);
  // A few rounds: a push moves the path nearer other cones, and pushes from both sides settle between them.
  for (int round = 0; round < 6 && r.worst_after > 1e-3; ++round) {
    std::vector<double> left(pts.size(), 0.0), right(pts.size(), 0.0);  // push to the left / to the right, m
    const double length = path.length();
    for (const auto& n : near) {
      // The end of the path: a cone beyond it is not beside it.
      if (n.foot.s <= 1e-6 || n.foot.s >= length - 1e-6) continue;
      auto& away = n.foot.lateral > 0 ? right : left;
      for (std::size_t i = 0; i < pts.size(); ++i) {
        const double d = std::abs(pts[i].s - n.foot.s);
        if (d < window)
          away[i] = std::max(away[i], n.shortfall * 0.5 * (1.0 + std::cos(std::numbers::pi * d / window)));
      }
    }
    for (std::size_t i = 0; i < pts.size(); ++i) {
      const double fade = std::clamp((pts[i].s - keep_start) / keep_start, 0.0, 1.0);  // the car's point stays put
      const Vec2 normal(-std::sin(pts[i].yaw), std::cos(pts[i].yaw));
      // Pushed from both sides, half the difference puts the point in the middle of the gap (a full step would
      // swing it past the middle and back, round after round).
      const double net = left[i] > 0 && right[i] > 0 ? 0.5 * (left[i] - right[i]) : left[i] - right[i];
      pts[i].p += fade * net * normal;
    }
    compute_geometry(path);
    near = too_near(path, cones, need);
    r.worst_after = worst(near);
  }
  return r;
}

}  // namespace fsd
