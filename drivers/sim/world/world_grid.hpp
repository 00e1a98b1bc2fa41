#pragma once
// Uniform 2D grid over the ground plane listing which bodies overlap each cell, walked along a ray's projection
// cell by cell (Amanatides & Woo) so a raycast tests only the bodies near the ray: its cost depends on the ray's
// length, not on how many objects the world holds.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "common/geometry.hpp"

namespace fsd::sim {

class UniformGrid {
 public:
  // boxes[i] is the xy extent of the item ids[i].
  void build(const std::vector<Eigen::AlignedBox2d>& boxes, const std::vector<std::uint32_t>& ids, double cell);

  std::span<const std::uint32_t> items(int ix, int iy) const {
    const auto c = static_cast<std::size_t>(iy) * static_cast<std::size_t>(nx_) + static_cast<std::size_t>(ix);
    return {items_.data() + start_[c], items_.data() + start_[c + 1]};
  }

  // Visits the cells that o + t·d crosses for t in [t0, t1], in order. visit(items, t_exit) returns true to stop
  // (e.g. once a hit nearer than t_exit is known). d need not be unit length in 2D: t is the caller's parameter.
  template <class Visit>
  void traverse(const Vec2& o, const Vec2& d, double t0, double t1, Visit&& visit) const {
    if (nx_ == 0) return;
    constexpr double kInf = std::numeric_limits<double>::infinity();
    for (int a = 0; a < 2; ++a) {  // clip to the grid's box (slabs)
      const double lo = a == 0 ? x0_ : y0_;
      const double hi = lo + (a == 0 ? nx_ : ny_) * cell_;
      if (std::abs(d[a]) < 1e-15) {
        if (o[a] < lo || o[a] > hi) return;
        continue;
      }
      double ta = (lo - o[a]) / d[a], tb = (hi - o[a]) / d[a];
      if (ta > tb) std::swap(ta, tb);
      t0 = std::max(t0, ta);
      t1 = std::min(t1, tb);
    }
    if (t0 > t1) return;
    const Vec2 p = o + d * t0;
    int ix = std::clamp(static_cast<int>(std::floor((p.x() - x0_) / cell_)), 0, nx_ - 1);
    int iy = std::clamp(static_cast<int>(std::floor((p.y() - y0_) / cell_)), 0, ny_ - 1);
    const int step_x = d.x() > 0 ? 1 : -1, step_y = d.y() > 0 ? 1 : -1;
    auto first_crossing = [&](double origin, double dir, double lo, int i) {
      if (std::abs(dir) < 1e-15) return kInf;
      return (lo + (i + (dir > 0 ? 1 : 0)) * cell_ - origin) / dir;
    };
    double t_max_x = first_crossing(o.x(), d.x(), x0_, ix);
    double t_max_y = first_crossing(o.y(), d.y(), y0_, iy);
    const double dt_x = std::abs(d.x()) < 1e-15 ? kInf : cell_ / std::abs(d.x());
    const double dt_y = std::abs(d.y()) < 1e-15 ? kInf : cell_ / std::abs(d.y());
    while (true) {
      const double t_exit = std::min({t_max_x, t_max_y, t1});
      if (visit(items(ix, iy), t_exit) || t_exit >= t1) return;
      if (t_max_x < t_max_y) {
        ix += step_x;
        if (ix < 0 || ix >= nx_) return;
        t_max_x += dt_x;
      } else {
        iy += step_y;
        if (iy < 0 || iy >= ny_) return;
        t_max_y += dt_y;
      }
    }
  }

 private:
  double x0_ = 0, y0_ = 0, cell_ = 1;
  int nx_ = 0, ny_ = 0;
  std::vector<std::uint32_t> start_;  // CSR: cell c holds items_[start_[c] .. start_[c+1])
  std::vector<std::uint32_t> items_;
};

}  // namespace fsd::sim
