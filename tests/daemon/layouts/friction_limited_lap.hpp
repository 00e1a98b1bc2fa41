#pragma once
// The friction-limited lap time of a track's true centre line, computed from the track file alone (no fsd code),
// and the plain 2D geometry it is built from (boundary ordering, resampling). The yardstick of lap 2 in the
// shared-layout and generated-layout sweeps (tests/daemon/layouts/all_tracks_test.cpp, generated_tracks_test.cpp).
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "tests/daemon/track_csv.hpp"

namespace fsd::test {

struct P2 {
  double x = 0, y = 0;
};
inline P2 operator+(P2 a, P2 b) { return {a.x + b.x, a.y + b.y}; }
inline P2 operator-(P2 a, P2 b) { return {a.x - b.x, a.y - b.y}; }
inline P2 operator*(double k, P2 a) { return {k * a.x, k * a.y}; }
inline double norm(P2 a) { return std::hypot(a.x, a.y); }
inline double dot(P2 a, P2 b) { return a.x * b.x + a.y * b.y; }

struct TrueCones {
  P2 start;
  double yaw = 0;
  std::vector<P2> left, right;
};

inline TrueCones read_cones(const std::string& file) {
  TrueCones t;
  for (const auto& r : read_track_csv(file)) {
    const P2 p{r.x, r.y};
    if (r.tag == "blue")
      t.left.push_back(p);
    else if (r.tag == "yellow")
      t.right.push_back(p);
    else if (r.tag == "car_start")
      t.start = p, t.yaw = r.direction;
  }
  return t;
}

// Boundary cones of a loop in driving order: from the cone nearest the start (not behind it), first step
// forwards, then always the nearest cone not yet taken; then untangled.
inline std::vector<P2> order_boundary(std::vector<P2> pts, P2 start, double yaw) {
  const P2 fwd{std::cos(yaw), std::sin(yaw)};
  std::vector<P2> out;
  std::size_t first = 0;
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const double c = norm(pts[i] - start) + (dot(pts[i] - start, fwd) < -1.0 ? 100.0 : 0.0);
    if (c < best) best = c, first = i;
  }
  out.push_back(pts[first]);
  pts.erase(pts.begin() + static_cast<long>(first));
  while (!pts.empty()) {
    std::size_t pick = 0;
    double pc = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < pts.size(); ++i) {
      double c = norm(pts[i] - out.back());
      if (out.size() == 1 && dot(pts[i] - out.back(), fwd) < 0) c += 1000.0;
      if (c < pc) pc = c, pick = i;
    }
    out.push_back(pts[pick]);
    pts.erase(pts.begin() + static_cast<long>(pick));
  }
  // The greedy order can jump across a narrow island (amz_fssim_thin) and come back later: shorten the loop by
  // reversing stretches (2-opt) until no reversal helps, keeping the first cone first and the driving direction.
  const std::size_t n = out.size();
  for (bool again = n >= 5; again;) {
    again = false;
    for (std::size_t i = 1; i + 1 < n; ++i)
      for (std::size_t j = i + 1; j < n; ++j) {
        const std::size_t k = (j + 1) % n;
        if (k == i - 1) continue;
        if (norm(out[i - 1] - out[j]) + norm(out[i] - out[k]) <
            norm(out[i - 1] - out[i]) + norm(out[j] - out[k]) - 1e-9) {
          std::reverse(out.begin() + static_cast<long>(i), out.begin() + static_cast<long>(j) + 1);
          again = true;
        }
      }
  }
  if (n >= 2 && dot(out[1] - out[0], fwd) < 0) std::reverse(out.begin() + 1, out.end());
  return out;
}

// A closed polyline resampled at (about) spacing ds.
inline std::vector<P2> resample_loop(const std::vector<P2>& poly, double ds) {
  std::vector<double> s{0};
  for (std::size_t i = 1; i <= poly.size(); ++i) s.push_back(s.back() + norm(poly[i % poly.size()] - poly[i - 1]));
  const double len = s.back();
  const auto n = static_cast<std::size_t>(std::round(len / ds));
  std::vector<P2> out;
  std::size_t seg = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const double q = len * static_cast<double>(k) / static_cast<double>(n);
    while (s[seg + 1] < q) ++seg;
    const double f = (q - s[seg]) / std::max(1e-12, s[seg + 1] - s[seg]);
    out.push_back(poly[seg] + f * (poly[(seg + 1) % poly.size()] - poly[seg]));
  }
  return out;
}

inline P2 closest_on_loop(const std::vector<P2>& poly, P2 p) {
  P2 best = poly.front();
  double bd = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const P2 a = poly[i], b = poly[(i + 1) % poly.size()];
    const double l2 = dot(b - a, b - a);
    const double f = l2 > 0 ? std::clamp(dot(p - a, b - a) / l2, 0.0, 1.0) : 0.0;
    const P2 q = a + f * (b - a);
    if (norm(p - q) < bd) bd = norm(p - q), best = q;
  }
  return best;
}

struct Limits {
  double mu, a_accel, a_brake, v_max;
};

// Centre line: midpoints of the left boundary's samples and their closest right-boundary points, resampled at
// 0.5 m and smoothed by a ±2 m moving average (the cones' placement ripple is no part of the track's shape).
// Curvature: the circle through the points 2 m before and after. Speed: min(√(μg/|κ|), v_max), then a periodic
// forward–backward pass under the friction circle with the traction and brake limits. Time: Σ ds / v̄.
inline double friction_limited_lap_time(const TrueCones& t, const Limits& lim, double* length = nullptr) {
  constexpr double g = 9.81, ds = 0.5;
  const auto left = resample_loop(order_boundary(t.left, t.start, t.yaw), 0.25);
  const auto right = order_boundary(t.right, t.start, t.yaw);
  std::vector<P2> mid;
  for (const P2& p : left) mid.push_back(0.5 * (p + closest_on_loop(right, p)));
  auto line = resample_loop(mid, ds);
  for (int pass = 0; pass < 2; ++pass) {
    const std::size_t n = line.size();  // each resampling may change the count
    std::vector<P2> sm(n);
    for (std::size_t i = 0; i < n; ++i) {
      P2 acc;
      for (int k = -4; k <= 4; ++k) acc = acc + line[(i + n + static_cast<std::size_t>(k + 4) - 4) % n];
      sm[i] = (1.0 / 9.0) * acc;
    }
    line = resample_loop(sm, ds);
  }
  const std::size_t m = line.size();
  std::vector<double> v(m), seg(m), kappa(m);
  for (std::size_t i = 0; i < m; ++i) {
    const P2 a = line[(i + m - 4) % m], b = line[i], c = line[(i + 4) % m];
    const double cross = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
    kappa[i] = 2.0 * std::abs(cross) / std::max(1e-9, norm(b - a) * norm(c - b) * norm(c - a));
    v[i] = kappa[i] < 1e-9 ? lim.v_max : std::min(lim.v_max, std::sqrt(lim.mu * g / kappa[i]));
    seg[i] = norm(line[(i + 1) % m] - line[i]);
  }
  auto grip_left = [&](double speed, std::size_t i) {
    const double ay = speed * speed * kappa[i];
    const double total = lim.mu * g;
    return ay >= total ? 0.0 : std::sqrt(total * total - ay * ay);
  };
  const auto slowest = static_cast<std::size_t>(std::min_element(v.begin(), v.end()) - v.begin());
  for (int round = 0; round < 2; ++round) {
    for (std::size_t k = 0; k < m; ++k) {
      const std::size_t i = (slowest + k) % m, j = (i + 1) % m;
      const double a = std::min(lim.a_accel, grip_left(v[i], i));
      v[j] = std::min(v[j], std::sqrt(v[i] * v[i] + 2 * a * seg[i]));
    }
    for (std::size_t k = 0; k < m; ++k) {
      const std::size_t j = (slowest + m - k) % m, i = (j + m - 1) % m;
      const double a = std::min(lim.a_brake, grip_left(v[j], j));
      v[i] = std::min(v[i], std::sqrt(v[j] * v[j] + 2 * a * seg[i]));
    }
  }
  double time = 0, len = 0;
  for (std::size_t i = 0; i < m; ++i) {
    time += seg[i] / (0.5 * (v[i] + v[(i + 1) % m]));
    len += seg[i];
  }
  if (length) *length = len;
  return time;
}

}  // namespace fsd::test
