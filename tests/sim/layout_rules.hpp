#pragma once
// Measures a layout file against the Formula Student Driverless rules from its cones alone: the independent
// checker of the layout generator's output (tests/sim/track_generator_test.cpp). It reads the CSV rows itself
// and shares no code with drivers/sim/track_generator. Boundaries are taken in the order the file lists them
// (the shared files and the generator list each boundary in driving order); a wrong order shows as gaps over
// 5 m, so it cannot pass unnoticed.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "tests/daemon/track_csv.hpp"

namespace fsd::test {

using V2 = Eigen::Vector2d;

struct LayoutRows {
  V2 start = V2::Zero();
  double yaw = 0;
  std::vector<V2> blue, yellow, orange, big_orange;
  int car_starts = 0, unknown = 0;
};

inline LayoutRows read_layout(const std::string& file) {
  LayoutRows l;
  for (const auto& r : read_track_csv(file)) {
    const V2 p(r.x, r.y);
    if (r.tag == "blue")
      l.blue.push_back(p);
    else if (r.tag == "yellow")
      l.yellow.push_back(p);
    else if (r.tag == "orange")
      l.orange.push_back(p);
    else if (r.tag == "big_orange")
      l.big_orange.push_back(p);
    else if (r.tag == "car_start")
      l.start = p, l.yaw = r.direction, ++l.car_starts;
    else
      ++l.unknown;
  }
  return l;
}

inline double cross2(const V2& a, const V2& b) { return a.x() * b.y() - a.y() * b.x(); }

inline double point_segment(const V2& p, const V2& a, const V2& b) {
  const V2 ab = b - a;
  const double l2 = ab.squaredNorm();
  const double f = l2 > 0 ? std::clamp((p - a).dot(ab) / l2, 0.0, 1.0) : 0.0;
  return (p - (a + f * ab)).norm();
}

inline bool segments_cross(const V2& a, const V2& b, const V2& c, const V2& d) {
  const double d1 = cross2(b - a, c - a), d2 = cross2(b - a, d - a), d3 = cross2(d - c, a - c),
               d4 = cross2(d - c, b - c);
  return ((d1 > 0) != (d2 > 0)) && ((d3 > 0) != (d4 > 0)) && d1 != 0 && d2 != 0 && d3 != 0 && d4 != 0;
}

// Radius of the circle through three points (infinite when they are in line); the sign says the turn a→b→c
// (positive left).
inline double circumradius(const V2& a, const V2& b, const V2& c, double* turn = nullptr) {
  const double cr = cross2(b - a, c - b);
  if (turn) *turn = cr;
  if (std::fabs(cr) < 1e-12) return std::numeric_limits<double>::infinity();
  return (b - a).norm() * (c - b).norm() * (c - a).norm() / (2.0 * std::fabs(cr));
}

// The boundary as a smooth curve through its cones (centripetal Catmull-Rom, 16 points a gap): within
// millimetres of the arc a row of cones stands on, where the straight chords cut a turn by its sagitta, and
// without the overshoot of the uniform form where the spacing changes at a turn's entry.
inline std::vector<V2> smooth_boundary(const std::vector<V2>& c, bool closed) {
  const std::size_t n = c.size();
  std::vector<V2> out;
  if (n < 3) return c;
  auto at = [&](long i) -> V2 {
    const long m = static_cast<long>(n);
    if (closed) return c[static_cast<std::size_t>((i % m + m) % m)];
    if (i < 0) return 2.0 * c[0] - c[1];  // reflected beyond an open end
    if (i >= m) return 2.0 * c[n - 1] - c[n - 2];
    return c[static_cast<std::size_t>(i)];
  };
  const long gaps = closed ? static_cast<long>(n) : static_cast<long>(n) - 1;
  for (long i = 0; i < gaps; ++i) {
    const V2 p0 = at(i - 1), p1 = at(i), p2 = at(i + 1), p3 = at(i + 2);
    const double t0 = 0, t1 = t0 + std::sqrt((p1 - p0).norm()), t2 = t1 + std::sqrt((p2 - p1).norm()),
                 t3 = t2 + std::sqrt((p3 - p2).norm());
    for (int k = 0; k < 16; ++k) {
      const double t = t1 + (t2 - t1) * k / 16.0;
      const V2 a1 = ((t1 - t) * p0 + (t - t0) * p1) / (t1 - t0);
      const V2 a2 = ((t2 - t) * p1 + (t - t1) * p2) / (t2 - t1);
      const V2 a3 = ((t3 - t) * p2 + (t - t2) * p3) / (t3 - t2);
      const V2 b1 = ((t2 - t) * a1 + (t - t0) * a2) / (t2 - t0);
      const V2 b2 = ((t3 - t) * a2 + (t - t1) * a3) / (t3 - t1);
      out.push_back(((t2 - t) * b1 + (t - t1) * b2) / (t2 - t1));
    }
  }
  if (!closed) out.push_back(c.back());
  return out;
}

inline double distance_to_polyline(const V2& p, const std::vector<V2>& line, bool closed) {
  double best = std::numeric_limits<double>::infinity();
  const std::size_t n = line.size();
  for (std::size_t i = 0; i + 1 < n + (closed ? 1 : 0); ++i)
    best = std::min(best, point_segment(p, line[i], line[(i + 1) % n]));
  return best;
}

// What the rules constrain on a trackdrive/autocross layout, measured from its cones.
struct CourseFigures {
  double width_min = 0, width_max = 0;               // each cone to the other boundary's smooth curve
  double cone_width_min = 0;                         // each cone to the nearest cone of the other boundary
  double gap_max = 0;                                // neighbouring cones along a boundary
  double gap_mean_tight = 0, gap_mean_straight = 0;  // in turns tighter than 10 m / between cones in line
  double gap_over_turn = 0;                          // largest gap over 1 m / the radius of the turn it is in (rad)
  double outer_radius_min = 0;                       // tightest outside of any turn (half its outside diameter)
  double straight_max = 0;                           // longest run of boundary cones in one line (2 cm)
  double length = 0;                                 // centre line: midpoints of the smooth boundaries
  bool boundaries_cross = false;                     // any two chords of the boundaries intersect
  double same_boundary_parts_min = 0;                // cones of one boundary on different parts of the track
  double left_right_min = 0;                         // any left cone to any right cone
  int slalom_lines = 0;  // runs of ≥ 4 cones in line 7.5–12 m apart, each on alternate sides
};

inline CourseFigures measure_course(const LayoutRows& l, bool closed) {
  CourseFigures f;
  const std::vector<V2>& L = l.blue;
  const std::vector<V2>& R = l.yellow;
  const auto sl = smooth_boundary(L, closed), sr = smooth_boundary(R, closed);
  f.width_min = f.cone_width_min = std::numeric_limits<double>::infinity();
  for (const V2& p : L)
    for (const V2& q : R) f.cone_width_min = std::min(f.cone_width_min, (p - q).norm());
  for (const V2& p : L) {
    const double d = distance_to_polyline(p, sr, closed);
    f.width_min = std::min(f.width_min, d), f.width_max = std::max(f.width_max, d);
  }
  for (const V2& p : R) {
    const double d = distance_to_polyline(p, sl, closed);
    f.width_min = std::min(f.width_min, d), f.width_max = std::max(f.width_max, d);
  }
  // Gaps, turn radii and straights along each boundary.
  f.outer_radius_min = std::numeric_limits<double>::infinity();
  double tight_sum = 0, straight_sum = 0;
  int tight_n = 0, straight_n = 0;
  for (int side : {1, -1}) {
    const std::vector<V2>& c = side > 0 ? L : R;
    const std::size_t n = c.size();
    const std::size_t gaps = closed ? n : n - 1;
    for (std::size_t i = 0; i < gaps; ++i) {
      const V2 a = c[i], b = c[(i + 1) % n];
      const double g = (b - a).norm();
      f.gap_max = std::max(f.gap_max, g);
      // The turn this gap is in: the circles through it and the cone before, and through it and the cone after;
      // a gap is in a turn as tight as the wider of the two (at a turn's entry one of them is the straight's).
      if (!closed && (i == 0 || i + 2 >= n)) continue;
      double turn = 0;
      const double r_after = circumradius(a, b, c[(i + 2) % n], &turn);
      const double r_before = circumradius(c[(i + n - 1) % n], a, b);
      const double r = std::max(r_after, r_before);
      if (r < 10.0) tight_sum += g, ++tight_n;
      if (std::min(r_after, r_before) > 1e3) straight_sum += g, ++straight_n;
      // Above the generator's 1 m floor (the inside of the tightest hairpins has a 1 m radius).
      if (std::isfinite(r) && g > 1.0 + 1e-3) f.gap_over_turn = std::max(f.gap_over_turn, g / r);
      // The outside of a turn: the left boundary of a right turn, the right boundary of a left turn.
      if ((side > 0 && turn < 0) || (side < 0 && turn > 0)) f.outer_radius_min = std::min(f.outer_radius_min, r_after);
    }
    // Longest run of cones within 2 cm of the line through its ends.
    for (std::size_t i = 0; i < gaps; ++i) {
      for (std::size_t len = 2; len <= n; ++len) {
        if (!closed && i + len >= n + 1) break;
        const V2 a = c[i], b = c[(i + len - 1) % n];
        bool in_line = true;
        for (std::size_t k = 1; k + 1 < len && in_line; ++k) in_line = point_segment(c[(i + k) % n], a, b) < 0.02;
        if (!in_line) break;
        f.straight_max = std::max(f.straight_max, (b - a).norm());
      }
    }
  }
  f.gap_mean_tight = tight_n ? tight_sum / tight_n : 0.0;
  f.gap_mean_straight = straight_n ? straight_sum / straight_n : 0.0;
  // Centre line length: each point of the smooth left boundary half way to its closest point on the right one.
  {
    std::vector<V2> mid;
    for (std::size_t i = 0; i < sl.size(); i += 2) {
      V2 best = sr.front();
      double bd = std::numeric_limits<double>::infinity();
      for (const V2& q : sr)
        if ((q - sl[i]).squaredNorm() < bd) bd = (q - sl[i]).squaredNorm(), best = q;
      mid.push_back(0.5 * (sl[i] + best));
    }
    for (std::size_t i = 1; i < mid.size(); ++i) f.length += (mid[i] - mid[i - 1]).norm();
    if (closed && mid.size() > 2) f.length += (mid.front() - mid.back()).norm();
  }
  // Chords crossing: left with right, and each with itself (not with its neighbours).
  auto chords = [&](const std::vector<V2>& c) {
    std::vector<std::pair<V2, V2>> s;
    for (std::size_t i = 0; i + 1 < c.size() + (closed ? 1 : 0); ++i) s.push_back({c[i], c[(i + 1) % c.size()]});
    return s;
  };
  const auto cl = chords(L), cr = chords(R);
  for (const auto& [a, b] : cl)
    for (const auto& [c, d] : cr) f.boundaries_cross = f.boundaries_cross || segments_cross(a, b, c, d);
  for (const auto* s : {&cl, &cr})
    for (std::size_t i = 0; i < s->size(); ++i)
      for (std::size_t j = i + 2; j < s->size(); ++j) {
        if (closed && i == 0 && j + 1 == s->size()) continue;
        f.boundaries_cross =
            f.boundaries_cross || segments_cross((*s)[i].first, (*s)[i].second, (*s)[j].first, (*s)[j].second);
      }
  // Parts of the track: two cones of one boundary are on different parts where the boundary between them is
  // more than π/2 times their distance (it turns through more than a half circle).
  f.same_boundary_parts_min = std::numeric_limits<double>::infinity();
  for (const auto* cp : {&L, &R}) {
    const auto& c = *cp;
    std::vector<double> s(c.size(), 0.0);
    for (std::size_t i = 1; i < c.size(); ++i) s[i] = s[i - 1] + (c[i] - c[i - 1]).norm();
    const double total = s.back() + (closed ? (c.front() - c.back()).norm() : 0.0);
    for (std::size_t i = 0; i < c.size(); ++i)
      for (std::size_t j = i + 1; j < c.size(); ++j) {
        double along = s[j] - s[i];
        if (closed) along = std::min(along, total - along);
        const double d = (c[i] - c[j]).norm();
        if (along > 0.5 * std::numbers::pi * d + 0.5)
          f.same_boundary_parts_min = std::min(f.same_boundary_parts_min, d);
      }
  }
  f.left_right_min = std::numeric_limits<double>::infinity();
  for (const V2& a : L)
    for (const V2& b : R) f.left_right_min = std::min(f.left_right_min, (a - b).norm());
  // Slalom lines: cones k, k+2, k+4, ... of one boundary interleaved with the other boundary's: look for ≥ 4
  // cones of either colour in one line (1 cm) at equal steps of 7.5–12 m whose colours alternate.
  {
    std::vector<std::pair<V2, int>> all;
    for (const V2& p : L) all.push_back({p, 1});
    for (const V2& p : R) all.push_back({p, -1});
    for (std::size_t i = 0; i < all.size(); ++i)
      for (std::size_t j = 0; j < all.size(); ++j) {
        if (all[i].second == all[j].second) continue;
        const V2 step = all[j].first - all[i].first;
        const double d = step.norm();
        if (d < 7.5 - 0.01 || d > 12.0 + 0.01) continue;
        int count = 2, colour = all[j].second;
        V2 next = all[j].first + step;
        for (bool found = true; found;) {
          found = false;
          for (const auto& [p, c] : all)
            if (c == -colour && (p - next).norm() < 0.01) {
              ++count, colour = c, next = p + step, found = true;
              break;
            }
        }
        if (count >= 4) ++f.slalom_lines;
      }
  }
  return f;
}

}  // namespace fsd::test
