// Raycasts against hand-computed geometry. Small cone: base radius R = 0.114, top radius 0.025, height 0.325, so
// its radius at height z is ρ(z) = 0.114 − 0.089·z/0.325; big cone: 0.1425, 0.03, 0.505.
#include <gtest/gtest.h>

#include <cmath>

#include "drivers/sim/world/world.hpp"
#include "drivers/sim/world/world_random.hpp"
#include "tests/sim/world_test_util.hpp"

namespace fsd::sim {
namespace {

using test::bare_config;
using test::make_cone;
using test::make_track;

TEST(WorldRaycast, HorizontalRayHitsSmallConeAtFrustumRadius) {
  const World world(make_track({make_cone(5.0, 0.0)}), bare_config(), 1);
  // z = 0.1: ρ = 0.114 − 0.089·0.1/0.325 = 0.0866154 → the ray along the axis hits at x = 5 − ρ.
  const auto hit = world.raycast(Vec3(0, 0, 0.1), Vec3::UnitX(), 50.0);
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->distance, 4.9133846, 1e-6);
  EXPECT_NEAR(hit->point.x(), 4.9133846, 1e-6);
  EXPECT_NEAR(hit->point.z(), 0.1, 1e-12);
  EXPECT_EQ(hit->cone, 0);
  EXPECT_EQ(hit->surface, Surface::ConeBody);  // 0.1/0.325 = 0.31, below the stripe (0.38..0.62)
  // Outward normal of the side: (−1, 0, k) normalised with k = 0.089/0.325 = 0.273846.
  EXPECT_NEAR(hit->normal.x(), -1.0 / std::hypot(1.0, 0.273846), 1e-5);
  EXPECT_NEAR(hit->normal.z(), 0.273846 / std::hypot(1.0, 0.273846), 1e-5);

  // 5 cm off the axis at the same height: x = 5 − sqrt(ρ² − 0.05²) = 5 − 0.0707264.
  const auto off = world.raycast(Vec3(0, 0.05, 0.1), Vec3::UnitX(), 50.0);
  ASSERT_TRUE(off);
  EXPECT_NEAR(off->distance, 4.9292736, 1e-6);
}

TEST(WorldRaycast, StripeBandHasItsOwnSurfaceAndReflectivity) {
  const World world(make_track({make_cone(5.0, 0.0, ConeRole::Left)}), bare_config(), 1);  // FSG: blue
  const auto body = world.raycast(Vec3(0, 0, 0.05), Vec3::UnitX(), 50.0);
  const auto stripe = world.raycast(Vec3(0, 0, 0.16), Vec3::UnitX(), 50.0);  // 0.16/0.325 = 0.49
  ASSERT_TRUE(body && stripe);
  EXPECT_EQ(body->surface, Surface::ConeBody);
  EXPECT_EQ(stripe->surface, Surface::ConeStripe);
  EXPECT_GT(stripe->reflectivity, body->reflectivity);  // white stripe on a blue cone

  const World yellow(make_track({make_cone(5.0, 0.0, ConeRole::Right)}), bare_config(), 1);
  const auto y_body = yellow.raycast(Vec3(0, 0, 0.05), Vec3::UnitX(), 50.0);
  const auto y_stripe = yellow.raycast(Vec3(0, 0, 0.16), Vec3::UnitX(), 50.0);
  ASSERT_TRUE(y_body && y_stripe);
  EXPECT_LT(y_stripe->reflectivity, y_body->reflectivity);  // black stripe on a yellow cone
}

// A beam straddling the stripe's lower edge (0.38 × 0.325 = 0.1235 m) returns the paints' mean over its footprint.
// Blue cone: body 22, stripe 95. Horizontal ray at z = 0.12 to the cone 5 m ahead: hit at t = 5 − ρ(0.12) =
// 4.918862; footprint 0.01 + 0.002·t = 0.0198377 m, i.e. [0.1100811, 0.1299189], of which 0.0064189 m is stripe.
TEST(WorldRaycast, ABeamAcrossTheStripeEdgeReturnsThePaintsMean) {
  const World world(make_track({make_cone(5.0, 0.0, ConeRole::Left)}), bare_config(), 1);
  const Vec3 origin(0, 0, 0.12);
  const auto point = world.raycast(origin, Vec3::UnitX(), 50.0);
  const auto beam = world.raycast(origin, Vec3::UnitX(), 50.0, Beam{0.01, 0.002});
  ASSERT_TRUE(point && beam);
  EXPECT_DOUBLE_EQ(point->reflectivity, 22.0);  // a point ray: the body at the hit
  EXPECT_EQ(beam->surface, Surface::ConeBody);  // the surface named is the one at the hit
  const double t = 5.0 - (0.114 - 0.089 * 0.12 / 0.325), footprint = 0.01 + 0.002 * t;
  const double on_stripe = 0.12 + footprint / 2 - 0.38 * 0.325;
  EXPECT_NEAR(beam->reflectivity, 22.0 + 73.0 * on_stripe / footprint, 1e-9);
  EXPECT_NEAR(beam->distance, point->distance, 1e-12);
  // Wholly inside the stripe or the body, the footprint changes nothing.
  EXPECT_DOUBLE_EQ(world.raycast(Vec3(0, 0, 0.16), Vec3::UnitX(), 50.0, Beam{0.01, 0.002})->reflectivity, 95.0);
  EXPECT_DOUBLE_EQ(world.raycast(Vec3(0, 0, 0.05), Vec3::UnitX(), 50.0, Beam{0.01, 0.002})->reflectivity, 22.0);
}

TEST(WorldRaycast, BigTimingConeIsTallerAndWider) {
  const World world(make_track({make_cone(5.0, 0.0, ConeRole::Timing)}), bare_config(), 1);
  ASSERT_TRUE(world.cones()[0].big);
  EXPECT_DOUBLE_EQ(world.cones()[0].height, 0.505);
  EXPECT_DOUBLE_EQ(world.cones()[0].base_width, 0.285);
  // z = 0.25: ρ = 0.1425 − 0.1125·0.25/0.505 = 0.0868069.
  const auto hit = world.raycast(Vec3(0, 0, 0.25), Vec3::UnitX(), 50.0);
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->distance, 5.0 - 0.0868069, 1e-6);
  // 0.45 m is above a small cone but still on the big one: ρ = 0.1425 − 0.1125·0.45/0.505 = 0.0422525.
  const auto high = world.raycast(Vec3(0, 0, 0.45), Vec3::UnitX(), 50.0);
  ASSERT_TRUE(high);
  EXPECT_NEAR(high->distance, 5.0 - 0.0422525, 1e-6);
}

TEST(WorldRaycast, RaysMissWhenTheyShould) {
  const World world(make_track({make_cone(5.0, 0.0)}), bare_config(), 1);
  EXPECT_FALSE(world.raycast(Vec3(0, 0, 0.4), Vec3::UnitX(), 50.0));    // over the 0.325 m cone, parallel to the ground
  EXPECT_FALSE(world.raycast(Vec3(0, 0.2, 0.1), Vec3::UnitX(), 50.0));  // beside it (ρ(0.1) = 0.087 < 0.2)
  EXPECT_FALSE(world.raycast(Vec3(0, 0, 0.1), -Vec3::UnitX(), 50.0));   // away from it
  EXPECT_FALSE(world.raycast(Vec3(0, 0, 0.1), Vec3::UnitX(), 4.9));     // out of range (hit at 4.913)
  EXPECT_FALSE(world.raycast(Vec3(0, 0, 0.3), Vec3(1, 0, 1).normalized(), 50.0));  // into the sky
  EXPECT_FALSE(world.raycast(Vec3(0, 0, -0.1), Vec3::UnitX(), 50.0));              // from below the ground
}

TEST(WorldRaycast, DownwardRayHitsTheSlopedGroundPlane) {
  WorldConfig cfg = bare_config();
  cfg.ground_slope_x = 0.05;
  cfg.ground_slope_y = -0.02;
  const World world(make_track({}), cfg, 1);
  EXPECT_DOUBLE_EQ(world.ground_height(1.0, 2.0), 0.05 - 0.04);
  // From (1, 2, 1) along (1, 0, −1)/√2: with s = t/√2, 1 − s = 0.05·(1 + s) − 0.04 → s = 0.99/1.05.
  const double s = 0.99 / 1.05;
  const auto hit = world.raycast(Vec3(1, 2, 1), Vec3(1, 0, -1).normalized(), 50.0);
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->distance, s * std::sqrt(2.0), 1e-9);
  EXPECT_NEAR(hit->point.x(), 1 + s, 1e-9);
  EXPECT_NEAR(hit->point.z(), 1 - s, 1e-9);
  EXPECT_EQ(hit->surface, Surface::Ground);
  EXPECT_DOUBLE_EQ(hit->reflectivity, cfg.ground_reflectivity);  // no texture
  const Vec3 n = Vec3(-0.05, 0.02, 1.0).normalized();
  EXPECT_NEAR(hit->normal.dot(n), 1.0, 1e-12);
  // Straight down from 2 m over (−3, 4): ground at −0.15 − 0.08 = −0.23.
  const auto down = world.raycast(Vec3(-3, 4, 2), -Vec3::UnitZ(), 50.0);
  ASSERT_TRUE(down);
  EXPECT_NEAR(down->distance, 2.23, 1e-12);
}

TEST(WorldRaycast, ConesStandOnTheSlopedGround) {
  WorldConfig cfg = bare_config();
  cfg.ground_slope_x = 0.03;
  const World world(make_track({make_cone(5.0, 1.0)}), cfg, 1);
  EXPECT_DOUBLE_EQ(world.cones()[0].base.z(), 0.15);
  // A ray just over the ground level at the cone hits the cone; one over its tip (0.15 + 0.325) does not.
  EXPECT_TRUE(world.raycast(Vec3(0, 1, 0.25), Vec3::UnitX(), 4.95));
  EXPECT_FALSE(world.raycast(Vec3(0, 1, 0.50), Vec3::UnitX(), 4.95));
}

TEST(WorldRaycast, NearestOfTwoObjectsWins) {
  const World world(make_track({make_cone(5.0, 0.0), make_cone(8.0, 0.0, ConeRole::Right)}), bare_config(), 1);
  const auto fwd = world.raycast(Vec3(0, 0, 0.1), Vec3::UnitX(), 50.0);
  ASSERT_TRUE(fwd);
  EXPECT_EQ(fwd->cone, 0);
  EXPECT_NEAR(fwd->distance, 4.9133846, 1e-6);
  const auto back = world.raycast(Vec3(10, 0, 0.1), -Vec3::UnitX(), 50.0);
  ASSERT_TRUE(back);
  EXPECT_EQ(back->cone, 1);
  EXPECT_NEAR(back->distance, 2.0 - 0.0866154, 1e-6);
  // A downward ray that meets the cone before the ground reports the cone.
  const auto down = world.raycast(Vec3(5.0, 0.0, 1.0), -Vec3::UnitZ(), 50.0);
  ASSERT_TRUE(down);
  EXPECT_EQ(down->cone, 0);
  EXPECT_NEAR(down->distance, 1.0 - 0.325, 1e-12);  // the flat top
}

// The grid index must find exactly what testing every cone finds.
TEST(WorldRaycast, GridIndexAgreesWithTestingEveryCone) {
  std::vector<TrackCone> cones;
  Rng rng(42);
  for (int i = 0; i < 300; ++i) cones.push_back(make_cone(rng.uniform(-30, 30), rng.uniform(-30, 30)));
  const World world(make_track(cones), bare_config(), 1);
  for (int k = 0; k < 2000; ++k) {
    const Vec3 o(rng.uniform(-35, 35), rng.uniform(-35, 35), rng.uniform(0.02, 0.3));
    const double a = rng.uniform(0, 2 * std::numbers::pi);
    const Vec3 d(std::cos(a), std::sin(a), 0.0);
    int want = -1;
    double want_t = 40.0;
    for (int i = 0; i < static_cast<int>(cones.size()); ++i) {
      const Vec3 base(cones[static_cast<std::size_t>(i)].position.x(), cones[static_cast<std::size_t>(i)].position.y(),
                      0);
      // Upright cone on flat ground: the cone's frame is the map frame moved to the base.
      const auto h = intersect_frustum(o - base, d, 0.114, 0.025, 0.325, 1e-9, want_t);
      if (h) {
        want = i;
        want_t = h->t;
      }
    }
    const auto got = world.raycast(o, d, 40.0);
    if (want < 0) {
      EXPECT_FALSE(got) << "ray " << k;
    } else {
      ASSERT_TRUE(got) << "ray " << k;
      EXPECT_EQ(got->cone, want) << "ray " << k;
      EXPECT_NEAR(got->distance, want_t, 1e-9) << "ray " << k;
    }
  }
}

}  // namespace
}  // namespace fsd::sim
