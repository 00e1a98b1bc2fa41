// Path geometry against formulas: circle curvature and heading, arc length, projection side and distance,
// windowed projection on a self-crossing path, wrapping on a closed path, smoothing of a noisy circle.
#include <gtest/gtest.h>

#include <numbers>
#include <random>

#include "control/planning/smoothing.hpp"
#include "tests/control/path_helpers.hpp"

namespace fsd {
namespace {

TEST(Path, CircleHasCurvatureOneOverRadiusAndTangentHeading) {
  const double r = 9.125;
  const Path p = test::circle_path({1, 2}, r, 200);
  // Chord polygon: perimeter 2·n·r·sin(π/n).
  EXPECT_NEAR(p.length(), 2 * 200 * r * std::sin(std::numbers::pi / 200), 1e-9);
  for (const auto& q : p.points) {
    EXPECT_NEAR(q.kappa, 1.0 / r, 1e-9);
    const Vec2 radial = q.p - Vec2(1, 2);
    EXPECT_NEAR(wrap_angle(q.yaw - std::atan2(radial.y(), radial.x()) - std::numbers::pi / 2), 0.0, 1e-9);
  }
}

TEST(Path, ProjectionGivesArcLengthAndSignedOffset) {
  const Path p = test::straight_path({0, 0}, 0.0, 10.0, 1.0);
  auto a = project(p, {3.5, 2.0});
  ASSERT_TRUE(a);
  EXPECT_NEAR(a->s, 3.5, 1e-12);
  EXPECT_NEAR(a->lateral, 2.0, 1e-12);  // left of a path heading +x is +y
  EXPECT_EQ(a->index, 3u);
  auto b = project(p, {7.25, -0.5});
  EXPECT_NEAR(b->lateral, -0.5, 1e-12);
  EXPECT_NEAR(b->foot.x(), 7.25, 1e-12);
  EXPECT_FALSE(project(Path{}, {0, 0}));
}

TEST(Path, WindowedProjectionStaysOnItsBranchOfAFigureEight) {
  // Two tangent circles sharing the point (0,0): right circle clockwise, then left circle counter-clockwise.
  Path p;
  const double r = 5.0;
  const int n = 100;
  for (int i = 0; i < n; ++i) {  // right circle, centre (0,−r), clockwise from the top
    const double a = std::numbers::pi / 2 - 2 * std::numbers::pi * i / n;
    p.points.push_back({Vec2(0, -r) + r * Vec2(std::cos(a), std::sin(a)), 0, 0, 0, 0});
  }
  for (int i = 0; i <= n; ++i) {  // left circle, centre (0,+r), counter-clockwise from the bottom
    const double a = -std::numbers::pi / 2 + 2 * std::numbers::pi * i / n;
    p.points.push_back({Vec2(0, r) + r * Vec2(std::cos(a), std::sin(a)), 0, 0, 0, 0});
  }
  compute_geometry(p);
  const double half = p.length() / 2;
  // Near the crossing, a hint on the first circle keeps the projection there.
  auto first = project(p, {0.05, 0.0}, half - 0.5, 2.0, 2.0);
  ASSERT_TRUE(first);
  EXPECT_NEAR(first->s, half, 0.2);
  auto second = project(p, {0.05, 0.0}, 1.0, 2.0, 2.0);
  EXPECT_NEAR(second->s, 0.0, 0.2);
  EXPECT_LT(second->s, 2.0);
}

TEST(Path, ClosedPathWrapsArcLength) {
  const Path p = test::circle_path({0, 0}, 10, 100);
  const double len = p.length();
  EXPECT_NEAR(normalize_s(p, len + 1.0), 1.0, 1e-9);
  EXPECT_NEAR(normalize_s(p, -1.0), len - 1.0, 1e-9);
  EXPECT_NEAR(s_difference(p, len - 1.0, 1.0), 2.0, 1e-9);
  const PathPoint q = sample(p, len - 1e-9);
  EXPECT_NEAR((q.p - p.points.front().p).norm(), 0.0, 1e-6);
}

TEST(Path, ResampleSpacingAndEnds) {
  const Path p = test::straight_path({0, 0}, 0.3, 10.0, 2.5);
  const Path r = resample(p, 0.4);
  ASSERT_EQ(r.points.size(), 26u);
  for (std::size_t i = 1; i + 1 < r.points.size(); ++i)
    EXPECT_NEAR((r.points[i].p - r.points[i - 1].p).norm(), 0.4, 1e-9);
  EXPECT_NEAR((r.points.back().p - p.points.back().p).norm(), 0.0, 1e-12);
}

TEST(Smoothing, NoisyCircleKeepsItsRadius) {
  std::mt19937 rng(3);
  std::normal_distribution<double> noise(0.0, 0.05);
  Path p = test::circle_path({0, 0}, 15.0, 400);
  for (auto& q : p.points) q.p += Vec2(noise(rng), noise(rng));
  const Path s = smooth_path(p, 0.25, 8.0);
  double max_dr = 0, max_dk = 0;
  for (const auto& q : s.points) {
    max_dr = std::max(max_dr, std::abs(q.p.norm() - 15.0));
    max_dk = std::max(max_dk, std::abs(q.kappa - 1.0 / 15.0));
  }
  EXPECT_LT(max_dr, 0.05);
  EXPECT_LT(max_dk, 0.02);  // raw three-point curvature of this noise is off by ~1/m
  EXPECT_TRUE(s.closed);
}

TEST(Smoothing, WithinARadiusEveryPointStaysInItsDisc) {
  // A right-angle corner (along x to the origin, then up y), points every 0.25 m. Smoothed over 12 m the
  // corner is cut by about a metre; held within 0.3 m of their places, no point moves further than that, and
  // where the free smoother moves points by less (far from the corner), both agree.
  std::vector<Vec2> pts;
  for (double x = -30; x < 0; x += 0.25) pts.emplace_back(x, 0.0);
  for (double y = 0; y <= 30; y += 0.25) pts.emplace_back(0.0, y);
  const double lambda = whittaker_lambda(12.0, 0.25);
  const auto free = whittaker_smooth(pts, false, lambda);
  const auto held = whittaker_smooth_within(pts, false, lambda, 0.3);
  ASSERT_EQ(held.size(), pts.size());
  double free_cut = 0, held_cut = 0;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    free_cut = std::max(free_cut, (free[i] - pts[i]).norm());
    held_cut = std::max(held_cut, (held[i] - pts[i]).norm());
    if (std::abs(pts[i].x()) + std::abs(pts[i].y()) > 15.0) {
      EXPECT_LT((held[i] - free[i]).norm(), 0.01) << i;
    }
  }
  EXPECT_GT(free_cut, 0.6);
  EXPECT_LE(held_cut, 0.3 + 1e-9);
  EXPECT_GT(held_cut, 0.29);  // the corner still uses its disc: the line is as smooth as the bound lets it be
  // A bound the free smoother never reaches changes nothing.
  const auto loose = whittaker_smooth_within(pts, false, lambda, 2.0 * free_cut);
  for (std::size_t i = 0; i < pts.size(); ++i) EXPECT_LT((loose[i] - free[i]).norm(), 0.01) << i;
}

}  // namespace
}  // namespace fsd
