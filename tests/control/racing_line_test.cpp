// Lap 2's minimum-curvature line on corridors whose best line is known by hand.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "control/racing_line.hpp"
#include "tests/control/path_helpers.hpp"

namespace fsd {
namespace {

double max_abs_kappa(const Path& p) {
  double k = 0;
  for (const auto& q : p.points) k = std::max(k, std::fabs(q.kappa));
  return k;
}

// A rounded square loop, counter-clockwise: four straights of `side` m joined by quarter circles of radius r.
Path rounded_square(double side, double r, double ds) {
  Path p;
  p.closed = true;
  const double h = side / 2;
  const Vec2 corners[4] = {{h, -h}, {h, h}, {-h, h}, {-h, -h}};  // corner-circle centres
  for (int c = 0; c < 4; ++c) {
    const double a0 = -std::numbers::pi / 2 + c * std::numbers::pi / 2;
    const Vec2 dir(std::cos(a0 + std::numbers::pi / 2), std::sin(a0 + std::numbers::pi / 2));
    const Vec2 start = corners[c] + r * Vec2(std::cos(a0), std::sin(a0)) - side * dir;
    for (double s = 0; s < side; s += ds) p.points.push_back({start + s * dir, 0, 0, 0, 0});
    const int k = static_cast<int>(std::round(r * std::numbers::pi / 2 / ds));
    for (int j = 0; j < k; ++j) {
      const double a = a0 + (std::numbers::pi / 2) * j / k;
      p.points.push_back({corners[c] + r * Vec2(std::cos(a), std::sin(a)), 0, 0, 0, 0});
    }
  }
  compute_geometry(p);
  return p;
}

TEST(RacingLine, ACircularTrackIsDrivenOnItsOuterEdge) {
  // The flattest closed line inside a ring is its outer circle: curvature 1/11 instead of 1/10.
  const Path centre = test::circle_path({0, 0}, 10.0, 252);
  const std::vector<double> room(centre.points.size(), 1.0);
  const auto r = minimum_curvature_line(centre, room, room);
  EXPECT_TRUE(r.converged);
  for (const auto& q : r.path.points) EXPECT_NEAR(q.p.norm(), 11.0, 0.02);
  EXPECT_NEAR(max_abs_kappa(r.path), 1.0 / 11.0, 0.003);
  EXPECT_NEAR(r.max_offset, 1.0, 1e-3);
}

TEST(RacingLine, CornersAreCutOutInOutWithinTheRoom) {
  // 20 m straights, corners of 4 m radius on the centre line, 1.2 m of room either side.
  const Path centre = rounded_square(20.0, 4.0, 0.25);
  const double room = 1.2;
  const std::vector<double> rooms(centre.points.size(), room);
  const auto r = minimum_curvature_line(centre, rooms, rooms);
  EXPECT_TRUE(r.converged);
  // Never further from the centre line than the room (a little for the re-linearisations).
  for (const auto& q : r.path.points) {
    const auto foot = project(centre, q.p);
    ASSERT_TRUE(foot);
    EXPECT_LE(foot->distance(), room + 0.02);
  }
  EXPECT_GT(r.max_offset, 0.9 * room);
  // The apex of each corner is on the inside (towards the loop's middle), the straights' middles well outside it.
  for (int c = 0; c < 4; ++c) {
    const double a = std::numbers::pi / 4 + c * std::numbers::pi / 2;
    const Vec2 corner_centre = 10.0 * Vec2(std::cos(a), std::sin(a)) * std::sqrt(2.0);
    const Vec2 apex_centre_line = corner_centre + 4.0 * Vec2(std::cos(a), std::sin(a));
    // The racing line's point nearest the corner's bisector ray.
    double best = 1e9, radial = 0;
    for (const auto& q : r.path.points) {
      const Vec2 d = q.p - corner_centre;
      const double off_ray = std::fabs(-std::sin(a) * d.x() + std::cos(a) * d.y());
      if (d.dot(Vec2(std::cos(a), std::sin(a))) > 0 && off_ray < best) best = off_ray, radial = d.norm();
    }
    EXPECT_LT(radial, (apex_centre_line - corner_centre).norm() - 0.8 * room) << "corner " << c;
  }
  // Flatter than the centre line: its corners are 1/4 m⁻¹.
  EXPECT_LT(max_abs_kappa(r.path), 0.75 * max_abs_kappa(centre));
}

TEST(RacingLine, NoRoomLeavesTheCentreLine) {
  const Path centre = rounded_square(20.0, 4.0, 0.25);
  const std::vector<double> none(centre.points.size(), 0.0);
  const auto r = minimum_curvature_line(centre, none, none);
  for (std::size_t i = 0; i < centre.points.size(); ++i)
    EXPECT_NEAR((r.path.points[i].p - centre.points[i].p).norm(), 0.0, 1e-9);
}

TEST(RacingLine, OpenPathsAndMismatchedRoomsAreLeftAlone) {
  const Path open = test::straight_path({0, 0}, 0.0, 20.0, 0.25);
  const std::vector<double> room(open.points.size(), 1.0);
  EXPECT_EQ(minimum_curvature_line(open, room, room).max_offset, 0.0);
  const Path loop = test::circle_path({0, 0}, 10.0, 100);
  EXPECT_EQ(minimum_curvature_line(loop, room, room).max_offset, 0.0);  // 81 rooms for 100 points
}

}  // namespace
}  // namespace fsd
