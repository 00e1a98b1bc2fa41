// SkidpadMission alone on a hand-made skid pad of the rules' size: circle centres (±9.125, 15), each marked by an
// inner ring (radius 7.625 m) and an outer ring (10.625 m) of cones, 16 to a ring, less those of the outer rings
// that would stand on the other circle's side of the entry axis. The car starts at the origin heading +y, 15 m
// before the crossing; the right circle (x > 0) comes first.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "control/missions/mission_skidpad.hpp"
#include "tests/control/mission_world.hpp"

namespace fsd {
namespace {

using test::cone_at;

constexpr double kCentreX = 9.125, kCentreY = 15.0, kDriven = 9.125;
const double kCircle = 2 * std::numbers::pi * kDriven;  // 57.33 m a lap

std::vector<Cone> skidpad_cones(double dx = 0.0) {
  std::vector<Cone> c;
  for (double side : {1.0, -1.0})
    for (double r : {7.625, 10.625})
      for (int k = 0; k < 16; ++k) {
        const double a = 2 * std::numbers::pi * k / 16;
        const double x = side * kCentreX + r * std::cos(a), y = kCentreY + r * std::sin(a);
        if (side * x < 1.0) continue;  // on the entry axis or beyond it
        c.push_back(cone_at(x + dx, y, side > 0 ? ConeColour::Yellow : ConeColour::Blue));
      }
  return c;
}

struct SkidpadTest : ::testing::Test {
  AutopilotConfig config;
  test::MissionWorld world;
  void SetUp() override { world.move(0.0, {0.0, 0.0}, std::numbers::pi / 2, 0.0); }
};

TEST_F(SkidpadTest, AStraightEntryUntilTheCirclesAreFitted) {
  SkidpadMission run(config, ColourConvention{});
  EXPECT_EQ(run.update_path(world.input(0.0)).path, nullptr);  // no cone map yet
  world.see(0.0, {cone_at(3, 5, ConeColour::Yellow), cone_at(-3, 5, ConeColour::Blue)});
  const MissionPath p = run.update_path(world.input(0.0));
  ASSERT_NE(p.path, nullptr);
  EXPECT_EQ(p.source, PathSource::Straight);
  EXPECT_TRUE(p.fixed);
  EXPECT_FALSE(run.geometry().has_value());
  // 30 m straight ahead of the start pose at skidpad_entry_speed.
  EXPECT_NEAR(p.path->length(), 30.0, 1e-9);
  EXPECT_NEAR(p.path->points.back().p.x(), 0.0, 1e-9);
  EXPECT_NEAR(p.path->points.back().p.y(), 30.0, 1e-9);
  for (const auto& q : p.path->points) ASSERT_EQ(q.v, config.mission.skidpad_entry_speed);
}

TEST_F(SkidpadTest, TheFigureOfEightOnceTheCirclesAreFitted) {
  SkidpadMission run(config, ColourConvention{});
  world.see(0.0, skidpad_cones());
  const MissionPath p = run.update_path(world.input(0.0));
  ASSERT_NE(p.path, nullptr);
  EXPECT_EQ(p.source, PathSource::Skidpad);
  EXPECT_TRUE(p.replaced);
  EXPECT_TRUE(p.fixed);
  ASSERT_TRUE(run.geometry());
  EXPECT_NEAR(run.geometry()->right.centre.x(), kCentreX, 1e-6);
  EXPECT_NEAR(run.geometry()->left.centre.x(), -kCentreX, 1e-6);
  // A quarter into each circle's first lap (away from the crossing's smoothing): on the circle, at the speed
  // of the skid pad's share of μ: v² / R = μ · mu_margin_skidpad · g.
  const double v = std::sqrt(config.speed.mu * config.speed.mu_margin_skidpad * 9.81 * kDriven);
  const double entry = 15.0;
  for (const auto& [s, centre] : {std::pair{entry + 0.25 * kCircle, Vec2(kCentreX, kCentreY)},
                                  std::pair{entry + 2.25 * kCircle, Vec2(-kCentreX, kCentreY)}}) {
    const PathPoint q = sample(*p.path, s);
    EXPECT_NEAR((q.p - centre).norm(), kDriven, 0.02) << s;
    EXPECT_NEAR(q.v, v, 0.02 * v) << s;
  }
  // Right circle first: half way round each, the car is at its far side.
  EXPECT_NEAR(sample(*p.path, entry + 0.5 * kCircle).p.x(), kCentreX + kDriven, 0.3);
  EXPECT_NEAR(sample(*p.path, entry + 2.5 * kCircle).p.x(), -kCentreX - kDriven, 0.3);
}

TEST_F(SkidpadTest, RefittedUntilTheLeftCircleAwayFromTheCrossings) {
  SkidpadMission run(config, ColourConvention{});
  world.see(0.0, skidpad_cones());
  run.update_path(world.input(0.0));
  run.start(world.input(0.0));
  const auto follow_at = [&](Stamp t, double s) {
    world.progress_s = s;
    const FollowResult f = test::followed_at(s);
    run.progress(world.input(t), &f);
  };
  // Still on the entry (5 m along): a new view moves the circles.
  world.progress_s = 5.0;
  world.see(0.1, skidpad_cones(0.2));
  EXPECT_TRUE(run.update_path(world.input(0.1)).replaced);
  EXPECT_NEAR(run.geometry()->right.centre.x(), kCentreX + 0.2, 1e-6);
  // Within 3 m of the crossing: the figure stays as it is.
  world.progress_s = 12.5;
  world.see(0.2, skidpad_cones(0.4));
  MissionPath p = run.update_path(world.input(0.2));
  EXPECT_FALSE(p.replaced);
  EXPECT_EQ(p.source, PathSource::Skidpad);
  EXPECT_NEAR(run.geometry()->right.centre.x(), kCentreX + 0.2, 1e-6);
  // Half way round the right circle (a fit from the entry can miss the far circle): refitted, and the car's place on
  // the new figure is where it was, not another pass of the crossing.
  follow_at(1.0, 16.0);
  const double half = 15.2 + 0.5 * kCircle;
  follow_at(3.0, half);
  world.move(3.0, {kCentreX + 0.4 + kDriven, kCentreY}, -std::numbers::pi / 2, 8.0);  // the circle's far side
  world.see(3.0, skidpad_cones(0.4));
  p = run.update_path(world.input(3.0));
  EXPECT_TRUE(p.replaced);
  EXPECT_NEAR(run.geometry()->right.centre.x(), kCentreX + 0.4, 1e-6);
  ASSERT_TRUE(p.resume_s.has_value());
  EXPECT_NEAR(*p.resume_s, half, 1.0);
  // On the left circle (past the third crossing): the figure stays.
  follow_at(10.0, 15.2 + 2 * kCircle + 1.0);
  world.progress_s = 15.2 + 2.5 * kCircle;
  world.see(12.0, skidpad_cones(0.6));
  EXPECT_FALSE(run.update_path(world.input(12.0)).replaced);
  EXPECT_NEAR(run.geometry()->right.centre.x(), kCentreX + 0.4, 1e-6);
}

TEST_F(SkidpadTest, EachCircleIsALapTimedCrossingToCrossingAndTheFourthEndsTheMission) {
  SkidpadMission run(config, ColourConvention{});
  world.see(0.0, skidpad_cones());
  run.update_path(world.input(0.0));
  run.start(world.input(0.0));
  auto at = [&](Stamp t, double s) {
    const FollowResult f = test::followed_at(s);
    return run.progress(world.input(t), &f).laps;
  };
  EXPECT_TRUE(at(1.0, 14.0).empty());
  EXPECT_TRUE(at(2.0, 16.0).empty());                                 // into the right circle: its clock starts
  EXPECT_TRUE(run.progress(world.input(2.5), nullptr).laps.empty());  // no path followed: nothing counts
  // Circle k ends at the crossing, 15 + k · 57.33 m along; each takes 6 s here.
  for (int k = 1; k <= 4; ++k) {
    const Stamp t = 2.0 + 6.0 * k;
    EXPECT_TRUE(at(t - 0.1, 15.0 + k * kCircle - 1.0).empty()) << k;
    EXPECT_FALSE(run.finished());
    const std::vector<LapEvent> laps = at(t, 15.0 + k * kCircle + 1.0);
    ASSERT_EQ(laps.size(), 1u) << k;
    EXPECT_EQ(laps[0].lap, k);
    EXPECT_DOUBLE_EQ(laps[0].t, t);
    EXPECT_NEAR(laps[0].time_s, 6.0, 1e-9);
  }
  EXPECT_TRUE(run.finished());
  EXPECT_TRUE(at(40.0, 15.0 + 4 * kCircle + 20.0).empty());
}

}  // namespace
}  // namespace fsd
