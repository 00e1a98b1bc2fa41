// The body's clearance from cones against hand-computed values: the rectangle of car.* at a pose, and swept along a
// known arc, where the outer front corner runs on √((R + w)² + f²) and the inner side on R − w about the centre.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "control/planning/footprint.hpp"
#include "tests/control/path_helpers.hpp"

namespace fsd {
namespace {

const Body kBody{2.4, 0.5, 0.7};

TEST(Footprint, ClearanceOfAConeAroundTheBodyByHand) {
  const Pose2 car{0, 0, 0};
  // Ahead of the nose, beside the body, off a corner, behind the tail, and inside.
  EXPECT_NEAR(body_clearance(car, {Vec2(3.0, 0.0), 0.1}, kBody), 0.6 - 0.1, 1e-12);
  EXPECT_NEAR(body_clearance(car, {Vec2(1.0, 1.0), 0.1}, kBody), 0.3 - 0.1, 1e-12);
  EXPECT_NEAR(body_clearance(car, {Vec2(1.0, -1.2), 0.1}, kBody), 0.5 - 0.1, 1e-12);
  EXPECT_NEAR(body_clearance(car, {Vec2(2.8, 1.0), 0.1}, kBody), 0.5 - 0.1, 1e-12);  // 3-4-5 off the corner
  EXPECT_NEAR(body_clearance(car, {Vec2(-0.9, 0.0), 0.1}, kBody), 0.4 - 0.1, 1e-12);
  EXPECT_NEAR(body_clearance(car, {Vec2(1.0, 0.0), 0.1}, kBody), -0.7 - 0.1, 1e-12);
  // The same cone seen from a car turned and moved: only the relative placement counts.
  const Pose2 turned{5.0, -2.0, 0.7};
  EXPECT_NEAR(body_clearance(turned, {turned.transform(Vec2(2.8, 1.0)), 0.1}, kBody), 0.4, 1e-12);
}

TEST(Footprint, TheBodySweptAlongAnArcReachesItsCornersRadius) {
  // Rear axle round a circle of radius R about the origin, counter-clockwise (the inside on the left).
  constexpr double R = 3.0;
  const Path arc = test::circle_path(Vec2::Zero(), R, 720);
  const double outer = std::hypot(R + kBody.half_width, kBody.front);  // the outer front corner's circle
  const double inner = R - kBody.half_width;                           // the inner side's nearest approach
  const double r = 0.1;
  for (const double margin : {0.0, 0.05}) {
    // Cones just outside the swept ring are clear by what is left; just inside it, they are short.
    const std::vector<Obstacle> clear{{Vec2(outer + r + margin + 0.01, 0.0), r}, {Vec2(0.0, inner - r - margin - 0.01), r}};
    const auto ok = sweep_body(arc, clear, kBody, margin, 0.01);
    EXPECT_FALSE(std::isfinite(ok.first_short_s)) << "margin " << margin;
    EXPECT_NEAR(ok.min_clearance, margin + 0.01, 2e-3);
    const std::vector<Obstacle> outer_hit{{Vec2(outer + r + margin - 0.01, 0.0), r}};
    EXPECT_TRUE(std::isfinite(sweep_body(arc, outer_hit, kBody, margin, 0.01).first_short_s));
    const std::vector<Obstacle> inner_hit{{Vec2(0.0, -(inner - r - margin + 0.01)), r}};
    EXPECT_TRUE(std::isfinite(sweep_body(arc, inner_hit, kBody, margin, 0.01).first_short_s));
  }
}

TEST(Footprint, PosesAreSweptInOrderAndTheFirstShortOneNamed) {
  std::vector<Pose2> poses;
  for (int i = 0; i <= 10; ++i) poses.push_back({0.5 * i, 0.0, 0.0});
  // A cone across the way at x = 5: the nose (2.4 ahead) reaches within 0.1 of its base at x = 2.5 - 0.1 + ...
  const std::vector<Obstacle> row{{Vec2(5.0, 0.0), 0.1}};
  const auto r = sweep_poses(poses, row, kBody, 0.2);
  // Pose i has the nose at 0.5 i + 2.4; clearance 5 − 0.1 − (0.5 i + 2.4) = 2.5 − 0.5 i < 0.2 first at i = 5.
  EXPECT_EQ(r.first_short, 5);
  EXPECT_EQ(r.obstacle, 0);
  EXPECT_NEAR(r.clearance, 0.0, 1e-12);
}

}  // namespace
}  // namespace fsd
