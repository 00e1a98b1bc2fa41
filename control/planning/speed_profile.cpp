#include "control/planning/speed_profile.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace fsd {

double SpeedProfile::curvature_limit(double kappa) const {
  const double k = std::abs(kappa);
  if (k < 1e-9) return limits_.v_max;
  return std::min(limits_.v_max, std::sqrt(limits_.mu * limits_.g / k));
}

double SpeedProfile::steering_limit(double kappa) const {
  const double k = std::abs(kappa);
  if (limits_.understeer <= 0 || k < 1e-9) return limits_.v_max;
  const double spare = limits_.max_steer - limits_.steer_reserve - std::atan(limits_.wheelbase * k);
  if (spare <= 0) return std::min(limits_.v_max, limits_.v_min);
  return std::clamp(std::sqrt(spare / (limits_.understeer * k)), limits_.v_min, limits_.v_max);
}

double stopping_speed(double distance, double decel, double latency) {
  if (!(distance > 0) || !(decel > 0)) return 0.0;
  const double at = decel * std::max(0.0, latency);
  return -at + std::sqrt(at * at + 2.0 * decel * distance);
}

double SpeedProfile::curvature_rate_limit(double dkappa_ds) const {
  const double k = std::abs(dkappa_ds);
  if (limits_.kappa_rate_max <= 0 || k < 1e-12) return limits_.v_max;
  return std::min(limits_.v_max, limits_.kappa_rate_max / k);
}

namespace {
// Caps every point's speed by the steering rate: dκ/ds over the window centred on it (the follower looks ahead
// and the steering starts turning before the bend, so the rate is judged over a stretch, not between neighbours).
void cap_by_curvature_rate(const SpeedProfile& profile, Path& path) {
  const SpeedLimits& l = profile.limits();
  auto& pts = path.points;
  const std::size_t n = pts.size();
  if (l.kappa_rate_max <= 0 || n < 3) return;
  const double half = 0.5 * l.kappa_rate_window;
  const double len = path.length();
  if (len < 1e-6) return;
  for (std::size_t i = 0; i < n; ++i) {
    const double s = pts[i].s;
    double a = s - half, b = s + half;
    if (!path.closed) {
      a = std::max(a, 0.0);
      b = std::min(b, len);
    }
    if (b - a < 1e-6) continue;
    const double dk = sample(path, b).kappa - sample(path, a).kappa;
    pts[i].v = std::min(pts[i].v, profile.curvature_rate_limit(dk / (b - a)));
  }
}

// Caps every point's speed by the steering's reach on the sharpest curvature within steer_window either side.
void cap_by_steering(const SpeedProfile& profile, Path& path) {
  const SpeedLimits& l = profile.limits();
  auto& pts = path.points;
  const std::size_t n = pts.size();
  if (l.understeer <= 0 || n == 0) return;
  const double len = path.length();
  // Distance along the path from point i to point j going `dir` (+1 ahead, −1 back), wrapping round a lap.
  auto along = [&](std::size_t i, std::size_t j, int dir) {
    const double d = dir > 0 ? pts[j].s - pts[i].s : pts[i].s - pts[j].s;
    return d >= 0 ? d : d + len;
  };
  std::vector<double> sharpest(n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    double k = std::abs(pts[i].kappa);
    for (const int dir : {-1, 1})
      for (std::size_t step = 1; step < n; ++step) {
        if (!path.closed && (dir > 0 ? i + step >= n : step > i)) break;
        const std::size_t j = dir > 0 ? (i + step) % n : (i + n - step) % n;
        if (along(i, j, dir) > l.steer_window) break;
        k = std::max(k, std::abs(pts[j].kappa));
      }
    sharpest[i] = k;
  }
  for (std::size_t i = 0; i < n; ++i) pts[i].v = std::min(pts[i].v, profile.steering_limit(sharpest[i]));
}

// Longitudinal grip left by the lateral acceleration v²κ on the friction circle.
double friction_left(const SpeedLimits& l, double v, double kappa) {
  const double total = l.mu * l.g;
  const double ay = v * v * std::abs(kappa);
  return ay >= total ? 0.0 : std::sqrt(total * total - ay * ay);
}
}  // namespace

double SpeedProfile::max_acceleration(double v, double kappa) const {
  double traction = limits_.a_accel_max;
  if (limits_.traction_ellipse) {
    // The driven (rear) tyres also carry their share of the cornering force: traction shrinks with the lateral
    // acceleration on an ellipse, not only where the friction circle's remainder falls below a_accel_max.
    const double lateral = v * v * std::abs(kappa) / (limits_.mu * limits_.g);
    traction *= lateral >= 1 ? 0.0 : std::sqrt(1 - lateral * lateral);
  }
  double a = std::min(friction_left(limits_, v, kappa), traction);
  if (limits_.power_max > 0 && limits_.mass > 0) a = std::min(a, limits_.power_max / (limits_.mass * std::max(v, 0.5)));
  return std::max(a, 0.0);
}

double SpeedProfile::max_deceleration(double v, double kappa) const {
  return std::max(0.0, std::min(friction_left(limits_, v, kappa), limits_.a_brake_max));
}

void SpeedProfile::apply(Path& path, double v_start, double v_end, const std::vector<SpeedZone>& zones) const {
  auto& pts = path.points;
  const std::size_t n = pts.size();
  if (n == 0) return;
  for (auto& p : pts) p.v = curvature_limit(p.kappa);
  cap_by_steering(*this, path);
  cap_by_curvature_rate(*this, path);
  if (!path.closed && v_end <= 0) {
    const double len = path.length();
    for (auto& p : pts)
      p.v = std::min(p.v, stopping_speed(len - p.s - limits_.stop_margin, limits_.a_brake_max, limits_.stop_latency));
  }
  for (const auto& z : zones)
    for (auto& p : pts) {
      const bool inside = z.s_begin <= z.s_end ? p.s >= z.s_begin && p.s <= z.s_end
                                               : path.closed && (p.s >= z.s_begin || p.s <= z.s_end);
      if (inside) p.v = std::min(p.v, std::max(0.0, z.v_max));
    }
  if (n == 1) {
    pts[0].v = std::min(pts[0].v, std::max(0.0, v_start));
    return;
  }
  const bool closed = path.closed && n >= 3;
  const double len = path.length();
  auto ds_between = [&](std::size_t i, std::size_t j) {  // j follows i
    return j > i ? pts[j].s - pts[i].s : len - pts[i].s + pts[j].s;
  };
  // Passes accelerate from one point to the next: v_next² ≤ v² + 2·a(v, κ)·ds.
  auto forward = [&](std::size_t i, std::size_t j) {
    const double v = pts[i].v;
    const double reach = std::sqrt(v * v + 2.0 * max_acceleration(v, pts[i].kappa) * ds_between(i, j));
    pts[j].v = std::min(pts[j].v, reach);
  };
  auto backward = [&](std::size_t j, std::size_t i) {  // i precedes j
    const double v = pts[j].v;
    const double reach = std::sqrt(v * v + 2.0 * max_deceleration(v, pts[j].kappa) * ds_between(i, j));
    pts[i].v = std::min(pts[i].v, reach);
  };
  if (!closed) {
    pts.front().v = std::min(pts.front().v, std::max(0.0, v_start));
    for (std::size_t i = 0; i + 1 < n; ++i) forward(i, i + 1);
    pts.back().v = std::min(pts.back().v, std::max(0.0, v_end));
    for (std::size_t j = n - 1; j > 0; --j) backward(j, j - 1);
    return;
  }
  // A lap: start both passes at the slowest curvature limit, where the speed is known to be at its limit,
  // and go once round.
  const auto start = static_cast<std::size_t>(
      std::min_element(pts.begin(), pts.end(), [](const PathPoint& a, const PathPoint& b) { return a.v < b.v; }) -
      pts.begin());
  for (std::size_t k = 0; k < n; ++k) forward((start + k) % n, (start + k + 1) % n);
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t j = (start + n - k) % n;
    backward(j, (j + n - 1) % n);
  }
}

void SpeedProfile::apply_until(Path& path, double v_start, double s_stop) const {
  Path part = path;
  part.closed = false;
  std::size_t keep = 0;
  while (keep < part.points.size() && part.points[keep].s <= s_stop + 1e-9) ++keep;
  part.points.resize(std::min(part.points.size(), std::max<std::size_t>(keep, 2)));
  apply(part, v_start, 0.0);
  for (std::size_t i = 0; i < path.points.size(); ++i) path.points[i].v = i < keep ? part.points[i].v : 0.0;
}

double travel_time(const Path& path) {
  const auto& pts = path.points;
  if (pts.size() < 2) return 0.0;
  double t = 0;
  const std::size_t segs = path.closed ? pts.size() : pts.size() - 1;
  for (std::size_t i = 0; i < segs; ++i) {
    const std::size_t j = (i + 1) % pts.size();
    const double ds = (pts[j].p - pts[i].p).norm();
    const double v = 0.5 * (pts[i].v + pts[j].v);
    if (v <= 1e-9) return ds > 1e-9 ? std::numeric_limits<double>::infinity() : t;
    t += ds / v;
  }
  return t;
}

}  // namespace fsd
