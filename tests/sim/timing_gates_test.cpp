#include <gtest/gtest.h>

#include "drivers/sim/world/timing_gates.hpp"

namespace fsd::sim {
namespace {

TEST(TimingGates, Track1HasOneGateBetweenItsBigOrangeCones) {
  // epfl_track_1: big orange at (±2.2, 4.7) and (±2.2, 7.3); the car starts at the origin heading +y.
  const TimingGates g(load_track("../shared/tracks/epfl_track_1.csv"));
  ASSERT_EQ(g.gates().size(), 1u);
  EXPECT_NEAR(g.gates()[0].centre.x(), 0.0, 1e-9);
  EXPECT_NEAR(g.gates()[0].centre.y(), 6.0, 1e-9);
  EXPECT_NEAR(g.gates()[0].half_width, 2.2, 1e-5);
  EXPECT_EQ(g.crossed({0.0, 5.9}, {0.3, 6.1}), 0u);
  EXPECT_FALSE(g.crossed({0.0, 6.1}, {0.0, 5.9}));  // backwards
  EXPECT_FALSE(g.crossed({5.0, 5.9}, {5.0, 6.1}));  // beside the gate
  EXPECT_FALSE(g.crossed({0.0, 1.0}, {0.0, 2.0}));
}

TEST(TimingGates, AccelerationHasStartAndFinishGates) {
  const TimingGates g(load_track("../shared/tracks/epfl_acceleration.csv"));
  ASSERT_EQ(g.gates().size(), 2u);
  const double d = (g.gates()[1].centre - g.gates()[0].centre).norm();
  EXPECT_NEAR(d, 75.0, 1.0);  // FS acceleration: 75 m between the timing lines
}

TEST(TimingGates, TrackWithoutTimingConesGetsAStartGate) {
  const Track t = load_track("../shared/tracks/epfl_VSV.csv");
  const TimingGates g(t);
  ASSERT_EQ(g.gates().size(), 1u);
  EXPECT_NEAR((g.gates()[0].centre - t.start.position()).norm(), 0.0, 1e-9);
}

}  // namespace
}  // namespace fsd::sim
