// Pushing a path off cones nearer than the body's half width: hand-placed cones beside a straight path.
#include <gtest/gtest.h>

#include "control/cone_clearance.hpp"

namespace fsd {
namespace {

Path straight(double length) {
  Path p;
  for (double x = 0; x <= length + 1e-9; x += 0.25) p.points.push_back({Vec2(x, 0), 0, 0, 0, 0});
  compute_geometry(p);
  return p;
}

TEST(ConeClearance, ACornerConeNearThePathPushesItAsideLocally) {
  Path p = straight(20);
  const std::vector<Vec2> cones{{10, 0.4}, {10, 3.0}};  // one 0.4 m left of the path, one well clear
  const auto r = keep_clear_of_cones(p, cones, 0.87, 3.0);
  EXPECT_EQ(r.cones_too_near, 1);
  EXPECT_NEAR(r.worst_before, 0.47, 1e-9);
  EXPECT_LT(r.worst_after, 0.01);
  // Beside the cone the path runs 0.87 m from it, i.e. at y ≈ 0.4 − 0.87 = −0.47; 3 m away it is untouched.
  EXPECT_NEAR(project(p, Vec2(10, 0.4))->distance(), 0.87, 0.01);
  EXPECT_NEAR(sample(p, 10.0).p.y(), -0.47, 0.02);
  for (const auto& q : p.points) {
    if (q.p.x() < 6.9 || q.p.x() > 13.1) {
      EXPECT_NEAR(q.p.y(), 0.0, 1e-9) << q.p.x();
    }
  }
}

TEST(ConeClearance, AGapNarrowerThanTheCarLeavesThePathInItsMiddle) {
  Path p = straight(20);
  // 1.4 m between the cones, the path 0.1 m off its middle: each side wants 0.87 m, 1.74 in all.
  const std::vector<Vec2> cones{{10, 0.6}, {10, -0.8}};
  const auto r = keep_clear_of_cones(p, cones, 0.87, 3.0);
  EXPECT_EQ(r.cones_too_near, 2);
  EXPECT_NEAR(sample(p, 10.0).p.y(), -0.1, 0.02);  // equally far from both
  EXPECT_NEAR(r.worst_after, 0.87 - 0.7, 0.02);    // and the shortfall says the gap is too narrow
}

TEST(ConeClearance, TheCarsOwnPointStaysAndClosedOrClearPathsAreLeftAlone) {
  Path p = straight(20);
  const Vec2 start = p.points.front().p;
  keep_clear_of_cones(p, {{1.0, 0.3}}, 0.87, 3.0);
  EXPECT_EQ(p.points.front().p, start);

  Path clear = straight(20);
  const auto r = keep_clear_of_cones(clear, {{10, 1.5}, {10, -1.5}}, 0.87, 3.0);
  EXPECT_EQ(r.cones_too_near, 0);
  for (const auto& q : clear.points) EXPECT_EQ(q.p.y(), 0.0);
}

}  // namespace
}  // namespace fsd
