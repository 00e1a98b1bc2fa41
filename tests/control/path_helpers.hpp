#pragma once
// Paths built from formulas for the control tests: circles, straights and their joins.
#include <cmath>
#include <numbers>

#include "control/planning/path.hpp"

namespace fsd::test {

// Counter-clockwise circle of radius r around c, n points, closed.
inline Path circle_path(const Vec2& c, double r, int n) {
  Path p;
  p.closed = true;
  for (int i = 0; i < n; ++i) {
    const double a = 2.0 * std::numbers::pi * i / n;
    p.points.push_back({c + r * Vec2(std::cos(a), std::sin(a)), 0, 0, 0, 0});
  }
  compute_geometry(p);
  return p;
}

// Straight from a along direction yaw, length len, spacing ds (open).
inline Path straight_path(const Vec2& a, double yaw, double len, double ds) {
  Path p;
  const Vec2 d(std::cos(yaw), std::sin(yaw));
  const int n = static_cast<int>(std::round(len / ds));
  for (int i = 0; i <= n; ++i) p.points.push_back({a + d * (ds * i), 0, 0, 0, 0});
  compute_geometry(p);
  return p;
}

}  // namespace fsd::test
