#include "control/planning/path.hpp"

#include <algorithm>
#include <cmath>

namespace fsd {

namespace {

std::size_t segment_count(const Path& path) {
  const std::size_t n = path.points.size();
  if (n < 2) return 0;
  return path.closed ? n : n - 1;
}

std::size_t next_index(const Path& path, std::size_t i) { return i + 1 < path.points.size() ? i + 1 : 0; }

// Arc length at the end of segment i.
double segment_end_s(const Path& path, std::size_t i) {
  return i + 1 < path.points.size() ? path.points[i + 1].s : path.length();
}

PathProjection project_on_segment(const Path& path, std::size_t i, const Vec2& point) {
  const PathPoint& a = path.points[i];
  const PathPoint& b = path.points[next_index(path, i)];
  const Vec2 ab = b.p - a.p;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 1e-12 ? std::clamp((point - a.p).dot(ab) / len2, 0.0, 1.0) : 0.0;
  PathProjection r;
  r.index = i;
  r.foot = a.p + t * ab;
  const double seg_len = segment_end_s(path, i) - a.s;
  r.s = a.s + t * seg_len;
  r.yaw = wrap_angle(a.yaw + t * wrap_angle(b.yaw - a.yaw));
  r.kappa = a.kappa + t * (b.kappa - a.kappa);
  r.v = a.v + t * (b.v - a.v);
  const Vec2 d = point - r.foot;
  // Side from the path tangent at the foot (segment direction, or the heading on a zero-length segment).
  const Vec2 tangent = len2 > 1e-12 ? Vec2(ab) : Vec2(std::cos(r.yaw), std::sin(r.yaw));
  r.lateral = cross2(tangent, d) >= 0 ? d.norm() : -d.norm();
  return r;
}

}  // namespace

double Path::length() const {
  if (points.size() < 2) return 0.0;
  const double open = points.back().s;
  return closed ? open + (points.front().p - points.back().p).norm() : open;
}

void transform_path(Path& path, const Pose2& by) {
  for (auto& q : path.points) {
    q.p = by.transform(q.p);
    q.yaw = wrap_angle(q.yaw + by.yaw);
  }
}

void compute_geometry(Path& path) {
  auto& pts = path.points;
  const std::size_t n = pts.size();
  if (n == 0) return;
  pts[0].s = 0;
  for (std::size_t i = 1; i < n; ++i) pts[i].s = pts[i - 1].s + (pts[i].p - pts[i - 1].p).norm();
  if (n < 2) return;
  const bool closed = path.closed && n >= 3;
  for (std::size_t i = 0; i < n; ++i) {
    const bool first = i == 0, last = i + 1 == n;
    const std::size_t ip = first ? (closed ? n - 1 : 0) : i - 1;
    const std::size_t in = last ? (closed ? 0 : n - 1) : i + 1;
    const Vec2 a = pts[i].p - pts[ip].p;  // incoming
    const Vec2 b = pts[in].p - pts[i].p;  // outgoing
    const Vec2 chord = pts[in].p - pts[ip].p;
    pts[i].yaw = std::atan2(chord.y(), chord.x());
    // Menger curvature: 2·sin(turn)/chord, i.e. the circle through the three points.
    const double denom = a.norm() * b.norm() * chord.norm();
    pts[i].kappa = (ip != i && in != i && denom > 1e-12) ? 2.0 * cross2(a, b) / denom : 0.0;
  }
  if (!closed && n >= 3) {
    // End points have no circle of their own: carry the neighbour's curvature.
    pts.front().kappa = pts[1].kappa;
    pts.back().kappa = pts[n - 2].kappa;
  }
}

double normalize_s(const Path& path, double s) {
  const double len = path.length();
  if (len <= 0) return 0.0;
  if (path.closed) {
    s = std::fmod(s, len);
    return s < 0 ? s + len : s;
  }
  return std::clamp(s, 0.0, len);
}

double s_difference(const Path& path, double a, double b) {
  double d = b - a;
  if (path.closed) {
    const double len = path.length();
    if (len > 0) {
      d = std::remainder(d, len);
    }
  }
  return d;
}

PathPoint sample(const Path& path, double s) {
  const auto& pts = path.points;
  if (pts.empty()) return {};
  if (pts.size() == 1) return pts.front();
  s = normalize_s(path, s);
  // Last point with points[i].s <= s.
  auto it = std::upper_bound(pts.begin(), pts.end(), s, [](double v, const PathPoint& p) { return v < p.s; });
  std::size_t i = it == pts.begin() ? 0 : static_cast<std::size_t>(it - pts.begin()) - 1;
  if (!path.closed && i + 1 >= pts.size()) return pts.back();
  const PathPoint& a = pts[i];
  const PathPoint& b = pts[next_index(path, i)];
  const double seg = segment_end_s(path, i) - a.s;
  const double t = seg > 1e-12 ? std::clamp((s - a.s) / seg, 0.0, 1.0) : 0.0;
  PathPoint r;
  r.p = a.p + t * (b.p - a.p);
  r.yaw = wrap_angle(a.yaw + t * wrap_angle(b.yaw - a.yaw));
  r.kappa = a.kappa + t * (b.kappa - a.kappa);
  r.v = a.v + t * (b.v - a.v);
  r.s = s;
  return r;
}

Path resample(const Path& input, double ds) {
  Path path = input;
  compute_geometry(path);  // arc lengths from the positions, whatever the input carried
  Path out;
  out.stamp = path.stamp;
  out.closed = path.closed;
  const double len = path.length();
  if (path.points.size() < 2 || len <= 0 || !(ds > 0)) return path;
  const auto n = static_cast<std::size_t>(std::ceil(len / ds - 1e-9));
  // A closed path does not repeat its first point; an open one ends exactly at its last point.
  const std::size_t count = path.closed ? std::max<std::size_t>(n, 3) : n + 1;
  const double step = path.closed ? len / static_cast<double>(count) : ds;
  out.points.reserve(count);
  for (std::size_t k = 0; k < count; ++k) {
    const double s = std::min(static_cast<double>(k) * step, len);
    out.points.push_back(sample(path, s));
  }
  if (!path.closed) out.points.back() = path.points.back();
  compute_geometry(out);
  return out;
}

std::optional<PathProjection> project(const Path& path, const Vec2& point) {
  const std::size_t segs = segment_count(path);
  if (segs == 0) return std::nullopt;
  std::optional<PathProjection> best;
  double best_d2 = 0;
  for (std::size_t i = 0; i < segs; ++i) {
    const PathProjection r = project_on_segment(path, i, point);
    const double d2 = (point - r.foot).squaredNorm();
    if (!best || d2 < best_d2) {
      best = r;
      best_d2 = d2;
    }
  }
  return best;
}

std::optional<PathProjection> project(const Path& path, const Vec2& point, double s_hint, double back, double ahead) {
  const std::size_t segs = segment_count(path);
  if (segs == 0) return std::nullopt;
  const double len = path.length();
  if (path.closed && back + ahead >= len) return project(path, point);
  const auto& pts = path.points;
  const double s0 = path.closed ? s_hint - back : std::max(0.0, s_hint - back);
  const double s1 = path.closed ? s_hint + ahead : std::min(len, s_hint + ahead);
  // First segment containing s0 (wrapped), then walk forward until s1.
  const double s0n = normalize_s(path, s0);
  auto it = std::upper_bound(pts.begin(), pts.end(), s0n, [](double v, const PathPoint& p) { return v < p.s; });
  std::size_t i = it == pts.begin() ? 0 : static_cast<std::size_t>(it - pts.begin()) - 1;
  if (i >= segs) i = segs - 1;
  std::optional<PathProjection> best;
  double best_d2 = 0;
  double covered = pts[i].s - s0n;  // arc length from s0 to the start of segment i (≤ 0)
  for (std::size_t k = 0; k < segs; ++k) {
    const PathProjection r = project_on_segment(path, i, point);
    const double d2 = (point - r.foot).squaredNorm();
    if (!best || d2 < best_d2) {
      best = r;
      best_d2 = d2;
    }
    const double seg = segment_end_s(path, i) - pts[i].s;
    covered += seg;
    if (covered >= s1 - s0) break;
    if (i + 1 < segs)
      ++i;
    else if (path.closed)
      i = 0;
    else
      break;
  }
  return best;
}

}  // namespace fsd
