#pragma once
// Measures a layout file against the Formula Student Driverless rules from its cones alone: the independent
// checker of the layout generator's output (tests/sim/track_generator_test.cpp). It reads the CSV rows itself
// and shares no code with drivers/sim/track_generator. Boundaries are taken in the order the file lists them
// (the shared files and the generator list each boundary in driving order); a wrong order shows as gaps over
// 5 m, so it cannot pass unnoticed. The second part measures what public layouts have beyond the rules (hairpin
// chains, the whole-lap circle, cones placed by hand, a narrowing; docs/track-generator.md), from the cones too.
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/QR>

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

// The first cone after cone i at least `d` from it (c.size() when there is none).
inline std::size_t at_least(const std::vector<V2>& c, std::size_t i, double d, bool closed) {
  const std::size_t n = c.size();
  for (std::size_t step = 1; step < n; ++step) {
    if (!closed && i + step >= n) break;
    const std::size_t k = (i + step) % n;
    if ((c[k] - c[i]).norm() >= d) return k;
  }
  return n;
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
      // The outside of a turn: the left boundary of a right turn, the right boundary of a left turn. Measured on
      // cones at least 2 m apart: closer ones (the densest turns) would let their sub-millimetre placement on the
      // boundary's chords swamp the curvature.
      const std::size_t j = at_least(c, i, 2.0, closed), k = j < n ? at_least(c, j, 2.0, closed) : n;
      if (k < n) {
        double wide_turn = 0;
        const double r_wide = circumradius(a, c[j], c[k], &wide_turn);
        if ((side > 0 && wide_turn < 0) || (side < 0 && wide_turn > 0))
          f.outer_radius_min = std::min(f.outer_radius_min, r_wide);
      }
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

// ---------------------------------------------------------------------------------------------------------------
// Beyond the rules: what public layouts have, measured from the cones alone.

struct Ring {
  V2 centre = V2::Zero();
  double radius = 0;
};

// Least-squares circle (Kåsa: x² + y² + D·x + E·y + F = 0).
inline Ring fit_circle(const std::vector<V2>& pts) {
  Eigen::MatrixXd a(static_cast<long>(pts.size()), 3);
  Eigen::VectorXd b(static_cast<long>(pts.size()));
  for (std::size_t i = 0; i < pts.size(); ++i) {
    a.row(static_cast<long>(i)) << pts[i].x(), pts[i].y(), 1.0;
    b(static_cast<long>(i)) = -pts[i].squaredNorm();
  }
  const Eigen::Vector3d s = a.colPivHouseholderQr().solve(b);
  Ring r;
  r.centre = V2(-0.5 * s(0), -0.5 * s(1));
  r.radius = std::sqrt(std::max(0.0, r.centre.squaredNorm() - s(2)));
  return r;
}

inline double max_residual(const Ring& r, const std::vector<V2>& pts) {
  double m = 0;
  for (const V2& p : pts) m = std::max(m, std::fabs((p - r.centre).norm() - r.radius));
  return m;
}

// The circle through three points; false when they are (nearly) in line.
inline bool circle_through(const V2& a, const V2& b, const V2& c, Ring* out) {
  const double d = 2.0 * cross2(b - a, c - a);
  if (std::fabs(d) < 1e-9) return false;
  const double ab = (b - a).squaredNorm(), ac = (c - a).squaredNorm();
  const V2 rel((ab * (c - a).y() - ac * (b - a).y()) / d, (ac * (b - a).x() - ab * (c - a).x()) / d);
  *out = {a + rel, rel.norm()};
  return true;
}

// Each cone's lane width: its distance to the smooth curve through the other boundary's cones.
inline std::vector<double> lane_widths(const std::vector<V2>& c, const std::vector<V2>& other_smooth, bool closed) {
  std::vector<double> w;
  for (const V2& p : c) w.push_back(distance_to_polyline(p, other_smooth, closed));
  return w;
}

inline double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
  return v[v.size() / 2];
}

// A cone out of its ring: its three neighbours either side stand exactly (2 mm: the cones stand on the boundary's
// chords, within a millimetre of its arcs) on one circle and it does not.
struct RingOutlier {
  std::size_t cone = 0;
  double offset = 0;  // m from the ring, positive away from its centre
  Ring ring;
};

inline std::vector<RingOutlier> ring_outliers(const std::vector<V2>& c, bool closed, double max_radius = 6.0) {
  std::vector<RingOutlier> out;
  const long n = static_cast<long>(c.size());
  auto at = [&](long i) { return c[static_cast<std::size_t>((i % n + n) % n)]; };
  for (long k = closed ? 0 : 2; k < (closed ? n : n - 2); ++k) {
    Ring r;
    if (!circle_through(at(k - 2), at(k - 1), at(k + 1), &r) || r.radius > max_radius) continue;
    auto on = [&](long i) { return std::fabs((at(i) - r.centre).norm() - r.radius) <= 0.002; };
    // Three ring cones either side: fewer could fall on one circle by chance (cones placed by hand), or by
    // symmetry (a slalom's bend puts two neighbours either side on one circle whatever its shape).
    if (!on(k + 2) || !on(k - 3) || !on(k + 3)) continue;
    const double off = (at(k) - r.centre).norm() - r.radius;
    if (std::fabs(off) > 0.02) out.push_back({static_cast<std::size_t>(k), off, r});
  }
  return out;
}

// Runs of at least four consecutive cones of one boundary exactly (5 mm) on one circle under max_radius, with
// the least-squares circle through them.
struct RingRun {
  std::size_t first = 0, last = 0;  // cone indices
  Ring ring;
  double span = 0;  // rad its cones cover about the centre
};

inline std::vector<RingRun> exact_rings(const std::vector<V2>& c, double max_radius) {
  std::vector<RingRun> runs;
  for (std::size_t i = 0; i + 2 < c.size();) {
    Ring r;
    if (!circle_through(c[i], c[i + 1], c[i + 2], &r) || r.radius > max_radius) {
      ++i;
      continue;
    }
    std::size_t j = i + 2;
    while (j + 1 < c.size() && std::fabs((c[j + 1] - r.centre).norm() - r.radius) < 0.005) ++j;
    if (j >= i + 3) {  // three cones are on a circle whatever they are; a fourth makes it a ring
      const Ring fit = fit_circle({c.begin() + static_cast<long>(i), c.begin() + static_cast<long>(j) + 1});
      double span = 0;
      for (std::size_t k = i; k < j; ++k) {
        const V2 a = c[k] - fit.centre, b = c[k + 1] - fit.centre;
        span += std::atan2(cross2(a, b), a.dot(b));
      }
      runs.push_back({i, j, fit, std::fabs(span)});
      i = j;
    } else {
      ++i;
    }
  }
  return runs;
}

// Turns whose cones of one boundary fit one circle (every cone within `tolerance`) of radius
// `radius_min`–`radius_max`, covering at least `min_span` about its centre. Grown from the best-fitting runs of
// five cones first, so that a turn is not begun on the straight before it, then trimmed back to its ring.
struct TurnArc {
  std::size_t first = 0, last = 0;
  V2 middle_cone = V2::Zero();
  Ring ring;
  double span = 0;  // rad the cones cover about the centre
  int turn = 0;     // +1 the track turns left (the centre on its left), -1 right
};

inline std::vector<TurnArc> turn_arcs(const std::vector<V2>& c, double tolerance, double radius_min, double radius_max,
                                      double min_span) {
  const std::size_t n = c.size();
  auto fit = [&](std::size_t i, std::size_t j, double* worst) {
    const std::vector<V2> pts(c.begin() + static_cast<long>(i), c.begin() + static_cast<long>(j) + 1);
    const Ring r = fit_circle(pts);
    *worst = r.radius >= radius_min && r.radius <= radius_max ? max_residual(r, pts)
                                                              : std::numeric_limits<double>::infinity();
    return r;
  };
  std::vector<std::pair<double, std::size_t>> seeds;
  for (std::size_t i = 0; i + 4 < n; ++i) {
    double worst = 0;
    fit(i, i + 4, &worst);
    if (worst <= tolerance) seeds.push_back({worst, i});
  }
  std::sort(seeds.begin(), seeds.end());
  std::vector<bool> used(n, false);
  std::vector<TurnArc> arcs;
  for (const auto& [residual, start] : seeds) {
    std::size_t i = start, j = start + 4;
    bool free = true;
    for (std::size_t k = i; k <= j; ++k) free = free && !used[k];
    if (!free) continue;
    double worst = 0;
    for (bool grew = true; grew;) {
      grew = false;
      if (j + 1 < n && !used[j + 1] && (fit(i, j + 1, &worst), worst <= tolerance)) ++j, grew = true;
      if (i > 0 && !used[i - 1] && (fit(i - 1, j, &worst), worst <= tolerance)) --i, grew = true;
    }
    for (std::size_t k = i; k <= j; ++k) used[k] = true;
    // Trim the ends back to the ring: a cone of the straight beyond a turn's end is off its circle by d²/2R,
    // within the tolerance for the first metre or two, and would widen the fit.
    Ring r = fit(i, j, &worst);
    for (bool trimmed = true; trimmed && j - i > 4;) {
      const double off_first = std::fabs((c[i] - r.centre).norm() - r.radius);
      const double off_last = std::fabs((c[j] - r.centre).norm() - r.radius);
      trimmed = std::max(off_first, off_last) > 0.6 * tolerance;
      if (trimmed) (off_first > off_last ? ++i : --j), r = fit(i, j, &worst);
    }
    double span = 0;
    for (std::size_t k = i; k < j; ++k) {
      const V2 a = c[k] - r.centre, b = c[k + 1] - r.centre;
      span += std::atan2(cross2(a, b), a.dot(b));
    }
    if (std::fabs(span) >= min_span) arcs.push_back({i, j, c[(i + j) / 2], r, std::fabs(span), span > 0 ? 1 : -1});
  }
  return arcs;
}

// Hairpin chains: hairpins at the tightest radius the lane width allows (one boundary's cones on an arc of 100°
// or more on the outside of the turn) linked when they turn opposite ways with no straight between them. Two arcs
// of the centre line that meet at an inflection have centres as far apart as their radii added; for the outer
// rings that is both outer radii less the lane width. A straight of length L between would add sqrt(L² + d²) − d.
struct ChainFigures {
  int hairpins = 0;                                   // outer arcs found
  int chains = 0;                                     // groups of two or more linked hairpins
  int longest = 0;                                    // hairpins in the longest chain
  double outer_radius_min = 0, outer_radius_max = 0;  // of the hairpins in chains
  // Each hairpin between two others of its chain turns from one inflection to the next, which lie on the lines
  // to its neighbours' centres: its angle (rad) from the centres alone.
  std::vector<double> middle_angles;
};

inline ChainFigures measure_chains(const LayoutRows& l, double width, double fit_tolerance, double radius_tolerance,
                                   double link_tolerance) {
  // The tightest hairpin a lane of this width has: the rules' 9 m outside diameter, or an island of 2 m inside
  // (the separation of docs/track-generator.md), whichever is wider.
  const double tightest = std::max(4.5, width + 1.0);
  std::vector<TurnArc> hairpins;
  for (int side : {1, -1})
    for (const TurnArc& a :
         turn_arcs(side > 0 ? l.blue : l.yellow, fit_tolerance, 3.5, tightest + 1.5, 100.0 * std::numbers::pi / 180))
      // The outside of the turn (the left boundary of a right turn) at the tightest radius.
      if (a.turn == -side && a.ring.radius <= tightest + radius_tolerance) hairpins.push_back(a);
  ChainFigures f;
  f.hairpins = static_cast<int>(hairpins.size());
  std::vector<std::size_t> group(hairpins.size());
  for (std::size_t i = 0; i < group.size(); ++i) group[i] = i;
  std::function<std::size_t(std::size_t)> root = [&](std::size_t i) {
    return group[i] == i ? i : group[i] = root(group[i]);
  };
  std::vector<std::vector<std::size_t>> linked(hairpins.size());
  for (std::size_t i = 0; i < hairpins.size(); ++i)
    for (std::size_t j = i + 1; j < hairpins.size(); ++j) {
      const TurnArc &a = hairpins[i], &b = hairpins[j];
      const double d = (a.ring.centre - b.ring.centre).norm();
      if (a.turn != b.turn && std::fabs(d - (a.ring.radius + b.ring.radius - width)) <= link_tolerance)
        linked[i].push_back(j), linked[j].push_back(i);
    }
  for (std::size_t i = 0; i < hairpins.size(); ++i) {
    if (linked[i].size() != 2) continue;
    const V2 c = hairpins[i].ring.centre;
    const V2 u1 = hairpins[linked[i][0]].ring.centre - c, u2 = hairpins[linked[i][1]].ring.centre - c;
    const double a = std::fabs(std::atan2(cross2(u1, u2), u1.dot(u2)));
    // The short way round or the long: the arc's middle (its middle cone) towards its neighbours or away.
    const V2 towards = u1.normalized() + u2.normalized(), middle = hairpins[i].middle_cone - c;
    f.middle_angles.push_back(towards.dot(middle) > 0 ? a : 2.0 * std::numbers::pi - a);
  }
  for (std::size_t i = 0; i < hairpins.size(); ++i)
    for (std::size_t j : linked[i]) group[root(i)] = root(j);
  std::vector<int> size(hairpins.size(), 0);
  for (std::size_t i = 0; i < hairpins.size(); ++i) ++size[root(i)];
  f.outer_radius_min = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < hairpins.size(); ++i) {
    if (size[root(i)] < 2) continue;
    if (root(i) == i) ++f.chains;
    f.longest = std::max(f.longest, size[root(i)]);
    f.outer_radius_min = std::min(f.outer_radius_min, hairpins[i].ring.radius);
    f.outer_radius_max = std::max(f.outer_radius_max, hairpins[i].ring.radius);
  }
  return f;
}

// The whole-lap circle: every boundary cone on one of two concentric rings, car_start between them.
struct CircleFigures {
  bool found = false;  // blue on one ring and yellow on another round (within 0.5 m) the same centre, no orange
  Ring inner, outer;   // least-squares fits
  int inner_cones = 0, outer_cones = 0;
  double inner_max = 0, outer_min = 0;  // farthest inner cone from the outer ring's centre, nearest outer one
  double start_radius = 0;              // the car's body's middle (1 m ahead of car_start) from the centre
  double start_heading_error = 0;       // rad between the car's heading and the circle's tangent there
  int direction = 0;                    // +1 counter-clockwise (a left turn)
  bool colours_as_driven = false;       // the inner ring blue when counter-clockwise, yellow when clockwise
  double gap_max = 0;                   // neighbouring cones of a ring, in the order listed
};

inline CircleFigures measure_circle(const LayoutRows& l) {
  CircleFigures f;
  if (l.blue.size() < 3 || l.yellow.size() < 3) return f;
  const Ring blue = fit_circle(l.blue), yellow = fit_circle(l.yellow);
  const bool blue_inner = blue.radius < yellow.radius;
  f.inner = blue_inner ? blue : yellow;
  f.outer = blue_inner ? yellow : blue;
  const auto& inner = blue_inner ? l.blue : l.yellow;
  const auto& outer = blue_inner ? l.yellow : l.blue;
  f.found = (blue.centre - yellow.centre).norm() < 0.5 && l.orange.empty() && l.big_orange.empty() &&
            max_residual(f.inner, inner) < 0.6 && max_residual(f.outer, outer) < 0.6;
  f.inner_cones = static_cast<int>(inner.size());
  f.outer_cones = static_cast<int>(outer.size());
  const V2 c = f.outer.centre;
  for (const V2& p : inner) f.inner_max = std::max(f.inner_max, (p - c).norm());
  f.outer_min = std::numeric_limits<double>::infinity();
  for (const V2& p : outer) f.outer_min = std::min(f.outer_min, (p - c).norm());
  // The car's body's middle: car_start is its rear axle, 2.5 m behind the nose and 0.5 m ahead of the tail.
  const V2 heading(std::cos(l.yaw), std::sin(l.yaw));
  const V2 radial = l.start + 1.0 * heading - c;
  f.start_radius = radial.norm();
  f.direction = cross2(radial, heading) > 0 ? 1 : -1;
  const V2 tangent = f.direction * V2(-radial.y(), radial.x()).normalized();
  f.start_heading_error = std::fabs(std::atan2(cross2(tangent, heading), tangent.dot(heading)));
  f.colours_as_driven = blue_inner == (f.direction > 0);
  for (const auto* ring : {&inner, &outer})
    for (std::size_t i = 0; i < ring->size(); ++i)
      f.gap_max = std::max(f.gap_max, ((*ring)[(i + 1) % ring->size()] - (*ring)[i]).norm());
  return f;
}

// The gaps along the straights of one boundary: maximal runs of six or more consecutive cones within 2 cm of
// the line through the run's ends, without the run's first and last gap (where the spacing turns into a turn's).
inline std::vector<std::vector<double>> straight_gaps(const std::vector<V2>& c) {
  std::vector<std::vector<double>> runs;
  for (std::size_t i = 0; i + 5 < c.size();) {
    auto in_line = [&](std::size_t a, std::size_t b) {
      for (std::size_t k = a + 1; k < b; ++k)
        if (point_segment(c[k], c[a], c[b]) > 0.02) return false;
      return true;
    };
    std::size_t j = i + 1;
    while (j + 1 < c.size() && in_line(i, j + 1)) ++j;
    if (j - i >= 5) {
      std::vector<double> gaps;
      for (std::size_t k = i + 1; k + 1 < j; ++k) gaps.push_back((c[k + 1] - c[k]).norm());
      runs.push_back(gaps);
      i = j;
    } else {
      ++i;
    }
  }
  return runs;
}

// How far p is off the circle through three neighbouring cones (the line through the middle two when they are
// in line): zero for a cone on the same arc or straight as its neighbours.
inline double off_curve(const V2& p, const V2& a, const V2& b, const V2& c) {
  Ring r;
  if (circle_through(a, b, c, &r) && r.radius < 1e4) return std::fabs((p - r.centre).norm() - r.radius);
  const V2 dir = (c - b).normalized();
  return std::fabs(cross2(dir, p - b));
}

// Cones placed by hand, an inner cone out of its ring, a narrowing: figures over both boundaries. A cone out of
// its ring stands at least kOutlierMin off the circle its ring neighbours are exactly on (radius under
// kTightRing), into the lane (the other boundary outside that circle).
inline constexpr double kTightRing = 5.0, kOutlierMin = 0.02;
inline constexpr double kLaneBelow = 3.0 - 0.002;  // under the rules' 3 m by more than a chord's millimetre
inline constexpr double kTightSpan = 100.0 * std::numbers::pi / 180.0;  // a turn, not a bend
struct HandFigures {
  double on_curve_share = 0;                // of cones within 2 mm of the arc through their neighbours (see off_curve)
  double gap_change_median = 0;             // neighbouring gaps (both 2 m or more): |difference| / their mean
  int outliers = 0;                         // inner cones out of an exact ring, into the lane
  double outlier_min = 0, outlier_max = 0;  // m they stand out
  int rings_without_outlier = 0;            // inner rings under 5 m whose exact cones cover 100° or more and that
                                            // carry no outlier
  int narrowings = 0;                       // runs of two or more cones of a boundary nearer than kLaneBelow to a
                                            // cone across (the outliers aside): a narrowing shows on both sides
  double narrowing_width = 0;               // m: the least distance across in them
  double narrowing_plateau = 0;             // m along a boundary over which the lane stays within 1 cm of that
  double narrowing_bend = 0;                // m: the plateau's cones off the line through its ends (0 on a straight)
  double outlier_lane_min = 0;              // m: the lane at an outlier (to the other boundary's smooth curve)
  double cone_width_min = 0;                // nearest cone across, without the outliers and the narrowing's cones
  double width_median = 0;                  // each cone to the other boundary's smooth curve
};

inline HandFigures measure_hand(const LayoutRows& l, bool closed) {
  HandFigures f;
  const std::vector<V2>* sides[2] = {&l.blue, &l.yellow};
  const std::vector<V2> smooth[2] = {smooth_boundary(l.blue, closed), smooth_boundary(l.yellow, closed)};
  std::vector<double> residuals, changes, widths;
  std::vector<bool> excluded[2];
  f.outlier_min = f.narrowing_width = f.outlier_lane_min = std::numeric_limits<double>::infinity();
  // Residuals, gaps, widths, and the cones out of their rings.
  for (int s = 0; s < 2; ++s) {
    const auto& c = *sides[s];
    const auto& other = smooth[1 - s];
    const long m = static_cast<long>(c.size());
    auto at = [&](long i) { return c[static_cast<std::size_t>((i % m + m) % m)]; };
    excluded[s].assign(c.size(), false);
    for (long k = closed ? 0 : 2; k < (closed ? m : m - 2); ++k) {
      residuals.push_back(std::min(off_curve(at(k), at(k - 2), at(k - 1), at(k + 1)),
                                   off_curve(at(k), at(k - 1), at(k + 1), at(k + 2))));
      const double g0 = (at(k) - at(k - 1)).norm(), g1 = (at(k + 1) - at(k)).norm();
      if (g0 >= 2.0 && g1 >= 2.0) changes.push_back(std::fabs(g1 - g0) / (0.5 * (g0 + g1)));
    }
    for (const double w : lane_widths(c, other, closed)) widths.push_back(w);
    std::vector<RingOutlier> inner;
    for (const RingOutlier& o : ring_outliers(c, closed, kTightRing))
      if (o.offset >= kOutlierMin && distance_to_polyline(o.ring.centre, other, closed) > o.ring.radius) {
        inner.push_back(o);
        excluded[s][o.cone] = true;
        f.outlier_lane_min = std::min(f.outlier_lane_min, distance_to_polyline(c[o.cone], other, closed));
        ++f.outliers;
        f.outlier_min = std::min(f.outlier_min, o.offset), f.outlier_max = std::max(f.outlier_max, o.offset);
      }
    for (const RingRun& r : exact_rings(c, kTightRing)) {
      if (r.span < kTightSpan || distance_to_polyline(r.ring.centre, other, closed) < r.ring.radius) continue;
      bool carried = false;
      for (const RingOutlier& o : inner)
        carried = carried ||
                  ((o.ring.centre - r.ring.centre).norm() < 0.02 && std::fabs(o.ring.radius - r.ring.radius) < 0.02);
      if (!carried) ++f.rings_without_outlier;
    }
  }
  // The narrowing: runs of two or more consecutive cones (outliers aside) nearer than kLaneBelow to a cone across.
  std::vector<double> across[2];
  for (int s = 0; s < 2; ++s) {
    const auto& c = *sides[s];
    across[s].assign(c.size(), std::numeric_limits<double>::infinity());
    for (std::size_t i = 0; i < c.size(); ++i)
      for (std::size_t j = 0; j < sides[1 - s]->size(); ++j)
        if (!excluded[1 - s][j]) across[s][i] = std::min(across[s][i], (c[i] - (*sides[1 - s])[j]).norm());
  }
  for (int s = 0; s < 2; ++s) {
    const auto& c = *sides[s];
    const std::size_t n = c.size();
    const std::vector<double>& w = across[s];
    std::vector<bool> narrow(n, false);
    for (std::size_t i = 0; i < n; ++i) narrow[i] = w[i] < kLaneBelow && !excluded[s][i];
    for (std::size_t i = 0; i < n;) {
      std::size_t j = i;
      while (narrow[i] && j + 1 < n && narrow[j + 1]) ++j;
      if (narrow[i] && j > i) {
        ++f.narrowings;
        double least = std::numeric_limits<double>::infinity();
        for (std::size_t k = i; k <= j; ++k) least = std::min(least, w[k]);
        f.narrowing_width = std::min(f.narrowing_width, least);
        std::size_t a = j, b = i;
        for (std::size_t k = i; k <= j; ++k)
          if (w[k] <= least + 0.01) a = std::min(a, k), b = std::max(b, k);
        double plateau = 0;
        for (std::size_t k = a; k < b; ++k) plateau += (c[k + 1] - c[k]).norm();
        f.narrowing_plateau = std::max(f.narrowing_plateau, plateau);
        for (std::size_t k = a; k <= b; ++k)
          f.narrowing_bend = std::max(f.narrowing_bend, std::fabs(cross2((c[b] - c[a]).normalized(), c[k] - c[a])));
      }
      i = j + 1;
    }
    for (std::size_t i = 0; i < n; ++i) excluded[s][i] = excluded[s][i] || narrow[i];
  }
  for (double r : residuals) f.on_curve_share += r < 0.002 ? 1.0 / static_cast<double>(residuals.size()) : 0.0;
  f.gap_change_median = median(changes);
  f.width_median = median(widths);
  f.cone_width_min = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < l.blue.size(); ++i)
    for (std::size_t j = 0; j < l.yellow.size(); ++j)
      if (!excluded[0][i] && !excluded[1][j])
        f.cone_width_min = std::min(f.cone_width_min, (l.blue[i] - l.yellow[j]).norm());
  return f;
}

// Which classes of public layouts a loop's cones show (what `--irregular` may draw), by the checker alone.
struct Seen {
  bool circle = false, chain = false, jittered = false, uneven = false, outlier = false, narrowing = false;
  HandFigures hand;
  ChainFigures chains;
};

inline Seen seen_in(const LayoutRows& l, bool closed) {
  Seen s;
  s.circle = measure_circle(l).found;
  if (s.circle) return s;
  s.hand = measure_hand(l, closed);
  // Cones placed exactly leave a third or more of them on the arc through their neighbours (straights, arcs);
  // cones moved by hand leave almost none (the slalom's, a narrowing's and an outlier's ring stay exact).
  s.jittered = s.hand.on_curve_share < 0.2;
  // Moved cones scatter about their ring (outward only at the tightest hairpins): a looser fit, a radius up to
  // 0.75 m wide of the tightest, and a link that would also take a straight under ~4.5 m between (the generator's
  // straights are 10 m or more).
  s.chains = s.jittered ? measure_chains(l, s.hand.width_median, 0.3, 0.75, 1.5)
                        : measure_chains(l, s.hand.width_median, 0.005, 0.05, 0.05);
  s.chain = s.chains.chains > 0;
  // Uneven gaps next to even ones; measurable where the cones are not also moved (jitter changes gaps too).
  s.uneven = !s.jittered && s.hand.gap_change_median > 0.04;
  s.outlier = s.hand.outliers > 0;
  s.narrowing = s.hand.narrowings > 0;
  return s;
}

// An acceleration lane's braking zone: how far its end row (the farthest orange cone along the lane) stands past
// the finish line (the mean of the four farther big orange cones of the eight). NaN without eight big orange cones.
inline double braking_zone(const LayoutRows& l) {
  const V2 fwd(std::cos(l.yaw), std::sin(l.yaw));
  std::vector<double> xs;
  for (const V2& p : l.big_orange) xs.push_back((p - l.start).dot(fwd));
  if (xs.size() != 8) return std::numeric_limits<double>::quiet_NaN();
  std::sort(xs.begin(), xs.end());
  const double finish = 0.25 * (xs[4] + xs[5] + xs[6] + xs[7]);
  double end = 0;
  for (const V2& p : l.orange) end = std::max(end, (p - l.start).dot(fwd));
  return end - finish;
}

}  // namespace fsd::test
