#include "control/cone_clearance.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace fsd {
namespace {

// The largest shortfall of any cone's distance from the path (0 when every cone is at least `need` away).
double worst_shortfall(const Path& path, const std::vector<Vec2>& cones, double need, int* count = nullptr) {
  double worst = 0;
  for (const auto& c : cones) {
    const auto f = project(path, c);
    if (!f || f->distance() >= need) continue;
    worst = std::max(worst, need - f->distance());
    if (count) ++*count;
  }
  return worst;
}

}  // namespace

ConeClearance keep_clear_of_cones(Path& path, const std::vector<Vec2>& cones, double need, double window,
                                  double keep_start) {
  ConeClearance r;
  auto& pts = path.points;
  if (path.closed || pts.size() < 4 || window <= 0) return r;
  r.worst_before = worst_shortfall(path, cones, need, &r.cones_too_near);
  r.worst_after = r.worst_before;
  if (r.cones_too_near == 0) return r;
  // A few rounds: a push moves the path nearer other cones, and pushes from both sides settle between them.
  for (int round = 0; round < 6 && r.worst_after > 1e-3; ++round) {
    std::vector<double> left(pts.size(), 0.0), right(pts.size(), 0.0);  // push to the left / to the right, m
    for (const auto& c : cones) {
      const auto f = project(path, c);
      if (!f || f->distance() >= need) continue;
      const double push = need - f->distance();
      // The end of the path: a cone beyond it is not beside it.
      if (f->s <= 1e-6 || f->s >= path.length() - 1e-6) continue;
      for (std::size_t i = 0; i < pts.size(); ++i) {
        const double d = std::abs(pts[i].s - f->s);
        if (d >= window) continue;
        const double w = 0.5 * (1.0 + std::cos(std::numbers::pi * d / window));
        (f->lateral > 0 ? right : left)[i] = std::max((f->lateral > 0 ? right : left)[i], push * w);
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
    r.worst_after = worst_shortfall(path, cones, need);
  }
  return r;
}

}  // namespace fsd
