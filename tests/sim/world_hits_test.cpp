// Cones the car's footprint touches: counted once, knocked over onto their side.
#include <gtest/gtest.h>

#include <array>
#include <cmath>

#include "drivers/sim/world/world.hpp"
#include "tests/sim/world_test_util.hpp"

namespace fsd::sim {
namespace {

using test::bare_config;
using test::make_cone;
using test::make_track;

std::array<Vec2, 4> box(double x0, double y0, double x1, double y1) {
  return {Vec2(x0, y0), Vec2(x1, y0), Vec2(x1, y1), Vec2(x0, y1)};
}

TEST(WorldHits, FootprintOverAConeCountsItOnceAndKnocksItOver) {
  World world(make_track({make_cone(5.0, 0.0), make_cone(9.0, 0.0)}), bare_config(), 1);
  const auto fp = box(4.0, -0.5, 5.2, 0.5);  // covers the first cone only
  EXPECT_EQ(world.update_hits(fp, 12.5), 1);
  EXPECT_EQ(world.cones_hit(), 1);
  EXPECT_TRUE(world.cones()[0].knocked);
  EXPECT_DOUBLE_EQ(world.cones()[0].hit_time, 12.5);
  EXPECT_FALSE(world.cones()[1].knocked);
  // Still touching it a moment later: no second count.
  EXPECT_EQ(world.update_hits(fp, 12.6), 0);
  EXPECT_EQ(world.cones_hit(), 1);
  EXPECT_DOUBLE_EQ(world.cones()[0].hit_time, 12.5);
}

TEST(WorldHits, FootprintBesideAConeDoesNotTouchIt) {
  World world(make_track({make_cone(5.0, 0.0)}), bare_config(), 1);
  // Base radius 0.114: an edge at y = 0.2 leaves 86 mm, at y = 0.1 it overlaps by 14 mm.
  EXPECT_EQ(world.update_hits(box(4.0, 0.2, 6.0, 1.2), 1.0), 0);
  EXPECT_FALSE(world.cones()[0].knocked);
  EXPECT_EQ(world.update_hits(box(4.0, 0.1, 6.0, 1.1), 2.0), 1);
  // A rotated footprint whose corner reaches 0.1 m from the centre.
  World other(make_track({make_cone(5.0, 0.0)}), bare_config(), 1);
  const double c = std::sqrt(0.5);
  const std::array<Vec2, 4> diamond{Vec2(5.1, 0), Vec2(5.1 + c, -c), Vec2(5.1 + 2 * c, 0), Vec2(5.1 + c, c)};
  EXPECT_EQ(other.update_hits(diamond, 1.0), 1);
  World far(make_track({make_cone(5.0, 0.0)}), bare_config(), 1);
  const std::array<Vec2, 4> far_diamond{Vec2(5.2, 0), Vec2(5.2 + c, -c), Vec2(5.2 + 2 * c, 0), Vec2(5.2 + c, c)};
  EXPECT_EQ(far.update_hits(far_diamond, 1.0), 0);
}

TEST(WorldHits, KnockedConeLiesOnItsSide) {
  World world(make_track({make_cone(5.0, 0.0)}), bare_config(), 1);
  // Upright, a ray at 0.28 m hits (ρ(0.28) = 0.0373 > 0).
  ASSERT_TRUE(world.raycast(Vec3(0, 0, 0.28), Vec3::UnitX(), 50.0));
  // The car comes from −x, so the cone falls towards +x, base where it stood.
  ASSERT_EQ(world.update_hits(box(4.0, -0.5, 4.95, 0.5), 3.0), 1);
  EXPECT_NEAR(world.cones()[0].fall_yaw, 0.0, 1e-12);
  // Lying, the cone's highest point is 2·R·cos θ = 2·0.114·0.964489 = 0.21990 (θ = atan(0.089/0.325)).
  EXPECT_FALSE(world.raycast(Vec3(0, 0, 0.28), Vec3::UnitX(), 50.0));
  EXPECT_FALSE(world.raycast(Vec3(0, 0, 0.225), Vec3::UnitX(), 50.0));
  // The base disc now faces −x, tilted by θ: its centre is at height R·cos θ = 0.109952, so a ray at 0.1 meets it
  // at x = 5 + (0.1 − 0.109952)·tan θ = 5 − 0.0027254.
  const auto base = world.raycast(Vec3(0, 0, 0.1), Vec3::UnitX(), 50.0);
  ASSERT_TRUE(base);
  EXPECT_EQ(base->cone, 0);
  EXPECT_NEAR(base->distance, 4.9972746, 1e-6);
  // Looking down on it: every hit lies between the ground and 0.2199 m, and the body reaches about
  // h·cos θ + top radius·sin θ = 0.3201 m along +x from where the base centre stood.
  double highest = 0, furthest = 0;
  for (double x = 4.8; x < 5.5; x += 0.01) {
    for (double y = -0.2; y < 0.2; y += 0.01) {
      const auto h = world.raycast(Vec3(x, y, 1.0), -Vec3::UnitZ(), 5.0);
      ASSERT_TRUE(h);
      if (h->cone != 0) continue;
      EXPECT_GE(h->point.z(), -1e-9);
      highest = std::max(highest, h->point.z());
      furthest = std::max(furthest, x);
    }
  }
  EXPECT_NEAR(highest, 0.2199, 0.005);
  EXPECT_NEAR(furthest, 5.0 + 0.3201, 0.015);
}

TEST(WorldHits, DegenerateFootprintHitsNothing) {
  World world(make_track({make_cone(0.0, 0.0)}), bare_config(), 1);
  const std::array<Vec2, 2> line{Vec2(-1, 0), Vec2(1, 0)};
  EXPECT_EQ(world.update_hits(line, 0.0), 0);
  EXPECT_EQ(world.cones_hit(), 0);
}

}  // namespace
}  // namespace fsd::sim
