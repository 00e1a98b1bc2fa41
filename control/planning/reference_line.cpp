#include "control/planning/reference_line.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "control/planning/path.hpp"
#include "control/planning/smoothing.hpp"

namespace fsd {

void compute_normals(ReferenceLine& ref) {
  const std::size_t n = ref.nodes.size();
  ref.normals.assign(n, Vec2::UnitY());
  if (n < 2) return;
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t a = ref.closed ? (i + n - 1) % n : (i == 0 ? 0 : i - 1);
    const std::size_t b = ref.closed ? (i + 1) % n : std::min(i + 1, n - 1);
    const Vec2 t = ref.nodes[b] - ref.nodes[a];
    if (t.norm() < 1e-9) {  // coincident neighbours: the previous node's normal
      if (i > 0) ref.normals[i] = ref.normals[i - 1];
      continue;
    }
    ref.normals[i] = Vec2(-t.y(), t.x()).normalized();
  }
}

ReferenceLine make_reference(const std::vector<Vec2>& polyline, bool closed, double ds, double wavelength) {
  ReferenceLine ref;
  ref.closed = closed;
  ref.ds = ds;
  if (polyline.size() < 2 || ds <= 0) return ref;
  Path raw;
  raw.closed = closed;
  for (const auto& p : polyline) raw.points.push_back({p, 0, 0, 0, 0});
  compute_geometry(raw);
  if (raw.length() < 1e-6) return ref;
  const Path even = wavelength > 0 ? smooth_path(raw, ds, wavelength) : resample(raw, ds);
  for (const auto& q : even.points) ref.nodes.push_back(q.p);
  compute_normals(ref);
  return ref;
}

namespace {

// Distance along the ray from `o` in direction `d` (unit) to its nearest crossing of the polyline; +inf if none
// within `reach`.
double ray_to_polyline(const Vec2& o, const Vec2& d, const std::vector<Vec2>& line, bool closed, double reach) {
  double best = std::numeric_limits<double>::infinity();
  const std::size_t n = line.size();
  if (n < 2) return best;
  const std::size_t segs = closed ? n : n - 1;
  for (std::size_t i = 0; i < segs; ++i) {
    const Vec2& a = line[i];
    const Vec2& b = line[(i + 1) % n];
    // Quick reject: the segment is out of reach.
    if ((a - o).norm() > reach + (b - a).norm()) continue;
    const Vec2 e = b - a;
    const double den = cross2(d, e);
    if (std::abs(den) < 1e-12) continue;
    const Vec2 w = a - o;
    const double t = cross2(w, e) / den;  // along the ray
    const double u = cross2(w, d) / den;  // along the segment
    if (t >= 0 && t <= reach && u >= 0 && u <= 1) best = std::min(best, t);
  }
  return best;
}

}  // namespace

std::vector<double> offsets_of(const ReferenceLine& ref, const std::vector<Vec2>& line, double reach) {
  std::vector<double> out(ref.nodes.size(), 0.0);
  for (std::size_t i = 0; i < ref.nodes.size(); ++i) {
    const double left = ray_to_polyline(ref.nodes[i], ref.normals[i], line, false, reach);
    const double right = ray_to_polyline(ref.nodes[i], -ref.normals[i], line, false, reach);
    if (std::isfinite(left) || std::isfinite(right)) out[i] = left <= right ? left : -right;
  }
  return out;
}

Room room_between(const ReferenceLine& ref, const std::vector<Vec2>& left, const std::vector<Vec2>& right,
                  bool boundaries_closed, double inset, double reach, double fallback) {
  Room room;
  const std::size_t n = ref.nodes.size();
  room.lo.resize(n);
  room.hi.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2& o = ref.nodes[i];
    const Vec2& nrm = ref.normals[i];
    double dl = ray_to_polyline(o, nrm, left, boundaries_closed, reach);
    double dr = ray_to_polyline(o, -nrm, right, boundaries_closed, reach);
    if (!std::isfinite(dl)) dl = fallback;
    if (!std::isfinite(dr)) dr = fallback;
    double hi = dl - inset, lo = -(dr - inset);
    if (lo > hi) lo = hi = 0.5 * (dl - dr);  // narrower than the car: only the middle
    room.lo[i] = lo;
    room.hi[i] = hi;
  }
  return room;
}

}  // namespace fsd
