// What nearer returns hide, on hand-placed points: a disc's visible share is the part of its azimuth span that no
// return nearer than its front covers (hand-computed spans), and the disc's own returns never hide it.
#include <gtest/gtest.h>

#include <cmath>

#include "perception/lidar_shadow.hpp"

namespace fsd {
namespace {

constexpr double kStep = 0.0034906585;  // 0.2°

Point at(double x, double y) {
  Point p;
  p.x = static_cast<float>(x), p.y = static_cast<float>(y);
  return p;
}

// Returns every 0.05° along a straight segment at range x from the origin, from y0 to y1.
std::vector<Point> segment(double x, double y0, double y1) {
  std::vector<Point> out;
  for (double a = std::atan2(y0, x); a <= std::atan2(y1, x); a += 0.0008) out.push_back(at(x, x * std::tan(a)));
  return out;
}

TEST(LidarShadow, InTheOpenEverythingShows) {
  LidarShadow s(kStep);
  s.build({}, Vec2::Zero());
  EXPECT_DOUBLE_EQ(s.visible_share(Vec2(5.0, 0.0), 0.114, 0.05), 1.0);
  // Farther returns and the disc's own hide nothing.
  auto pts = segment(8.0, -1.0, 1.0);
  for (const auto& p : segment(4.9, -0.1, 0.1)) pts.push_back(p);
  s.build(pts, Vec2::Zero());
  EXPECT_DOUBLE_EQ(s.visible_share(Vec2(5.0, 0.0), 0.114, 0.05), 1.0);
}

TEST(LidarShadow, ANearerObjectHidesItsShareOfTheSpan) {
  LidarShadow s(kStep);
  // A board at 3 m covering the azimuths from 0 to +1 rad: the disc at 6 m on the x axis has half its span hidden.
  s.build(segment(3.0, 0.0, 3.0), Vec2::Zero());
  EXPECT_NEAR(s.visible_share(Vec2(6.0, 0.0), 0.114, 0.05), 0.5, 0.05);
  // Wholly behind it, and wholly clear of it on the other side.
  EXPECT_NEAR(s.visible_share(Vec2(6.0, 1.0), 0.114, 0.05), 0.0, 1e-9);
  EXPECT_NEAR(s.visible_share(Vec2(6.0, -1.0), 0.114, 0.05), 1.0, 1e-9);
  // The sensor elsewhere: from (0, 4) the board (y ≤ 3 at x = 3) no longer lies between it and the disc at (6, 4).
  s.build(segment(3.0, 0.0, 3.0), Vec2(0.0, 4.0));
  EXPECT_NEAR(s.visible_share(Vec2(6.0, 4.0), 0.114, 0.05), 1.0, 1e-9);
}

TEST(LidarShadow, AcrossTheBackOfTheSensor) {
  // A disc straight behind the sensor spans the azimuth ±π seam; a board behind covering y ≥ 0 hides half of it
  // (to a bin: the span is 12 bins of 0.2°).
  LidarShadow s(kStep);
  std::vector<Point> pts;
  for (double y = 0.0; y < 1.0; y += 0.001) pts.push_back(at(-3.0, y));
  s.build(pts, Vec2::Zero());
  EXPECT_NEAR(s.visible_share(Vec2(-6.0, 0.0), 0.114, 0.05), 0.5, 0.09);
}

}  // namespace
}  // namespace fsd
