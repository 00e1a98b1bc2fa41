// PoseHistory against poses worked out by hand: interpolation, the heading across ±π, holding at the ends,
// capacity, and poses out of order.
#include <gtest/gtest.h>

#include <numbers>

#include "localization/pose_history.hpp"

namespace fsd {
namespace {

constexpr double kPi = std::numbers::pi;

TEST(PoseHistory, EmptyHasNoPose) {
  PoseHistory h;
  EXPECT_FALSE(h.at(0.0).has_value());
  EXPECT_FALSE(h.newest().has_value());
}

TEST(PoseHistory, InterpolatesPositionAndHeading) {
  PoseHistory h;
  h.add(1.0, {0.0, 0.0, 0.0});
  h.add(2.0, {10.0, -4.0, 0.5});
  const Pose2 p = *h.at(1.25);
  EXPECT_NEAR(p.x, 2.5, 1e-12);
  EXPECT_NEAR(p.y, -1.0, 1e-12);
  EXPECT_NEAR(p.yaw, 0.125, 1e-12);
}

TEST(PoseHistory, HeadingTakesTheShorterArcAcrossPi) {
  PoseHistory h;
  h.add(0.0, {0, 0, kPi - 0.1});
  h.add(1.0, {0, 0, -kPi + 0.1});  // 0.2 rad on, through ±π
  EXPECT_NEAR(std::abs(h.at(0.5)->yaw), kPi, 1e-12);
  EXPECT_NEAR(h.at(0.25)->yaw, kPi - 0.05, 1e-12);
  EXPECT_NEAR(h.at(0.75)->yaw, -kPi + 0.05, 1e-12);
}

TEST(PoseHistory, HoldsTheNearestPoseOutsideItsSpan) {
  PoseHistory h;
  h.add(1.0, {1, 2, 0.1});
  h.add(2.0, {3, 4, 0.2});
  EXPECT_DOUBLE_EQ(h.at(0.0)->x, 1.0);
  EXPECT_DOUBLE_EQ(h.at(5.0)->y, 4.0);
  EXPECT_DOUBLE_EQ(*h.newest(), 2.0);
}

TEST(PoseHistory, KeepsOnlyTheNewestPosesAndIgnoresOlderOnes) {
  PoseHistory h(3);
  for (int i = 0; i < 5; ++i) h.add(i, {static_cast<double>(i), 0, 0});
  EXPECT_EQ(h.size(), 3u);
  EXPECT_DOUBLE_EQ(h.at(0.0)->x, 2.0);  // 0 and 1 are gone: the oldest kept holds
  h.add(3.5, {100, 0, 0});              // older than the newest (4): ignored
  EXPECT_DOUBLE_EQ(h.at(3.5)->x, 3.5);
  h.add(4.0, {8, 0, 0});  // the same instant: replaces it
  EXPECT_DOUBLE_EQ(h.at(4.0)->x, 8.0);
  EXPECT_EQ(h.size(), 3u);
  // What at() clamps to is not a pose of that instant: the history reaches back to its oldest kept pose only.
  EXPECT_FALSE(h.reaches_back_to(1.0));
  EXPECT_TRUE(h.reaches_back_to(2.0));
  EXPECT_TRUE(h.reaches_back_to(9.0));  // ahead of the newest: the newest holds (a scan's last firing)
  EXPECT_FALSE(PoseHistory().reaches_back_to(0.0));
}

TEST(PoseHistory, CorrectMovesEachPoseByTheCorrectionOfItsInstant) {
  PoseHistory h;
  h.add(1.0, {1, 0, 0});
  h.add(2.0, {2, 0, 0});
  // Identity up to 1.5 s, then 1 m to the left and a quarter turn about the map's origin.
  h.correct([](Stamp t) { return t < 1.5 ? Pose2{} : Pose2{0, 1, kPi / 2}; });
  EXPECT_NEAR(h.at(1.0)->x, 1.0, 1e-12);
  const Pose2 moved = *h.at(2.0);
  EXPECT_NEAR(moved.x, 0.0, 1e-12);
  EXPECT_NEAR(moved.y, 3.0, 1e-12);
  EXPECT_NEAR(moved.yaw, kPi / 2, 1e-12);
}

}  // namespace
}  // namespace fsd
