// Lap counting: crossings in the direction of travel only, hysteresis against jitter at the line, lap times
// from interpolated crossing times, timing lines from the shared tracks' big orange cones.
#include <gtest/gtest.h>

#include <numbers>

#include "control/missions/lap_counter.hpp"
#include "tests/control/track_truth.hpp"

namespace fsd {
namespace {


TEST(LapCounter, CountsForwardCrossingsWithInterpolatedTimes) {
  // Line across x = 0 (from y = +2 to y = −2), travel +x. The car drives a 100 m loop at 10 m/s: straight
  // through the line, then away and back; positions sampled every 0.1 s.
  TimingLine line{{0, 2}, {0, -2}, {1, 0}};
  LapCounter lc(line, {10.0, 5.0, 1.0});
  auto pos = [](double t) {  // circle of circumference 100 m through (0,0) heading +x
    const double r = 100.0 / (2 * std::numbers::pi), a = 10.0 * t / r;
    return Vec2(r * std::sin(a), r - r * std::cos(a));
  };
  std::vector<LapEvent> events;
  for (double t = -0.55; t < 25.0; t += 0.1)
    if (auto e = lc.update(t, pos(t))) events.push_back(*e);
  // Crossings at t = 0, 10, 20: two completed laps of 10 s each.
  ASSERT_EQ(events.size(), 2u);
  EXPECT_EQ(events[0].lap, 1);
  EXPECT_NEAR(events[0].t, 10.0, 0.01);
  EXPECT_NEAR(events[0].time_s, 10.0, 0.01);
  EXPECT_NEAR(events[1].time_s, 10.0, 0.01);
  EXPECT_EQ(lc.laps_completed(), 2);
}

TEST(LapCounter, JitterAtTheLineAndBackwardCrossingsDoNotCount) {
  TimingLine line{{0, 2}, {0, -2}, {1, 0}};
  LapCounter lc(line, {10.0, 5.0, 1.0});
  double t = 0;
  // Approach, cross, then wobble back and forth across the line for a while: one crossing only.
  for (double x = -5; x <= 0.5; x += 0.5) lc.update(t += 0.1, {x, 0});
  EXPECT_TRUE(lc.timing());
  for (int k = 0; k < 20; ++k) EXPECT_FALSE(lc.update(t += 1.0, {k % 2 ? 0.3 : -0.3, 0}));
  // Reverse through the line: no lap.
  for (double x = 0.5; x >= -15; x -= 0.5) EXPECT_FALSE(lc.update(t += 0.1, {x, 0}));
  // Crossing outside the line's ends (beside the track): no lap.
  for (double x = -15; x <= 15; x += 0.5) EXPECT_FALSE(lc.update(t += 0.1, {x, 8.0}));
  EXPECT_EQ(lc.laps_completed(), 0);
  // Come back round and cross properly: lap 1.
  for (double x = -15; x <= 1; x += 0.5) lc.update(t += 0.1, {x, 0});
  EXPECT_EQ(lc.laps_completed(), 1);
}

TEST(LapCounter, ALapRoundOneTightTurnCounts) {
  // The car round a circle of 3 m radius (the rules' 9 m hairpin as a whole lap, 18.8 m), never more than 6 m from
  // its line across the start: every pass over the line after the first is a lap, at 3 m/s one each 6.3 s.
  const Pose2 start{3.0, 0.0, std::numbers::pi / 2};
  LapCounter lc(line_across(start), {});
  lc.start_timing_at(0.0);
  const double r = 3.0, v = 3.0;
  for (double t = 0.02; t < 20.0; t += 0.02) {
    const double a = v * t / r;
    lc.update(t, {r * std::cos(a), r * std::sin(a)});
  }
  ASSERT_EQ(lc.laps_completed(), 3);
  for (const double lap : lc.lap_times()) EXPECT_NEAR(lap, 2 * std::numbers::pi * r / v, 0.03);
}

TEST(LapCounter, TimingLinesOfTheSharedTracks) {
  // epfl_track_1: big orange at x = ±2.2, y = 4.7 and 7.3; start at the origin heading +y.
  const Track t1 = test::shared_track("epfl_track_1");
  const auto l1 = timing_line_from_cones(cones_of(t1), t1.start, t1.convention);
  ASSERT_TRUE(l1);
  EXPECT_NEAR(l1->mid().x(), 0.0, 1e-9);
  EXPECT_NEAR(l1->mid().y(), 6.0, 1e-9);
  EXPECT_NEAR(l1->forward.y(), 1.0, 1e-9);
  EXPECT_NEAR((l1->a - l1->b).norm(), 4.4, 1e-9);
  EXPECT_GT(l1->a.x() * -1, 0);  // a is the left end (x < 0 when heading +y)
  // Acceleration: start line at y = 5.089, finish at y = 80.089 (75 m apart).
  const Track acc = test::shared_track("epfl_acceleration");
  const auto start = timing_line_from_cones(cones_of(acc), acc.start, acc.convention, 0, 10, 200);
  const auto finish = timing_line_from_cones(cones_of(acc), acc.start, acc.convention, 1, 10, 200);
  ASSERT_TRUE(start && finish);
  EXPECT_NEAR(finish->mid().y() - start->mid().y(), 75.0, 1e-9);
  // epfl_21_05_2023 starts 5 m past its line (heading −y, line at y = +5).
  const Track t21 = test::shared_track("epfl_21_05_2023");
  const auto l21 = timing_line_from_cones(cones_of(t21), t21.start, t21.convention);
  ASSERT_TRUE(l21);
  EXPECT_NEAR(l21->past(t21.start.position()), 5.0, 1e-9);
  // No timing cones: nothing (the caller then uses a line through the start pose).
  const Track vsv = test::shared_track("epfl_VSV");
  EXPECT_FALSE(timing_line_from_cones(cones_of(vsv), vsv.start, vsv.convention));
  const TimingLine across = line_across(vsv.start, 5.0);
  EXPECT_NEAR(across.past(vsv.start.position() + Vec2(0, 1)), 1.0, 1e-12);
}

TEST(LapCounter, TimingConesOnOneSideStillGiveALineAcrossTheStartHeading) {
  // epfl_autoX_Vaudoise_Sponso doubles its start line: big orange at x = ±1.5, y = 7 and 8, with a blue and two
  // yellow boundary cones at y = 7.5 between them. A cone map merges each side into one cone and may vote the
  // right one yellow: only the left timing cone is left. The line must still lie at y = 7.5, across the track.
  const Track ax = test::shared_track("epfl_autoX_Vaudoise_Sponso");
  std::vector<Cone> mapped;
  for (const Cone& c : cones_of(ax)) {
    const bool start_line = std::abs(c.position.y() - 7.5) <= 0.5 && std::abs(std::abs(c.position.x()) - 1.5) < 0.01;
    if (!start_line) mapped.push_back(c);
  }
  Cone left;
  left.position = Vec3(-1.5, 7.5, 0);
  left.colour = ax.convention.timing;
  mapped.push_back(left);
  Cone right = left;
  right.position = Vec3(1.5, 7.5, 0);
  right.colour = ax.convention.right;
  mapped.push_back(right);
  const auto line = timing_line_from_cones(mapped, ax.start, ax.convention);
  ASSERT_TRUE(line);
  // Asked for timing cones on both sides (an open course's finish line), one side is no line.
  EXPECT_FALSE(timing_line_from_cones(mapped, ax.start, ax.convention, 0, 10.0, 40.0, true));
  EXPECT_NEAR(line->forward.y(), 1.0, 1e-5);
  EXPECT_NEAR(line->past(ax.start.position()), -9.0, 1e-5);  // start at y = −1.5
  // Its ends span the lane (x from −1.5 to +2): a car on the centre line crosses it between them.
  EXPECT_NEAR(line->a.x(), -1.5, 1e-5);
  EXPECT_NEAR(line->b.x(), 2.0, 1e-5);
  LapCounter lc(*line, {10.0, 5.0, 1.0});
  EXPECT_FALSE(lc.update(0.0, {0.0, -5.0}));
  EXPECT_FALSE(lc.update(1.0, {0.0, 6.5}));
  EXPECT_FALSE(lc.timing());
  lc.update(2.0, {0.0, 8.5});  // crosses y = 7.5 at t = 1.5: the first lap starts
  EXPECT_TRUE(lc.timing());
  ASSERT_TRUE(lc.last_crossing());
  EXPECT_NEAR(*lc.last_crossing(), 1.5, 1e-5);
}

TEST(LapCounter, StartPastTheLineTimesTheFirstLapFromTheStart) {
  TimingLine line{{0, 2}, {0, -2}, {1, 0}};
  LapCounter lc(line, {10.0, 5.0, 1.0});
  lc.start_timing_at(3.0);
  lc.update(3.0, {5, 0});
  EXPECT_FALSE(lc.update(3.1, {5.5, 0}));
  for (double x = 6; x < 30; x += 1) lc.update(4.0, {x, 0});  // drive away (armed)
  lc.update(40.0, {-1, 0});
  const auto e = lc.update(41.0, {1, 0});
  ASSERT_TRUE(e);
  EXPECT_NEAR(e->time_s, 40.5 - 3.0, 1e-9);
}

}  // namespace
}  // namespace fsd
