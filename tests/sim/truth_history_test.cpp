// The virtual car's recent physics steps: a time anywhere in them is posed between the two steps around it (hand
// computed), not between the last two; outside them, the nearest end; the history keeps its bound.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "drivers/sim/vehicle/truth_history.hpp"

namespace fsd::sim {
namespace {

// A step at t of a car driving +x at 20 m/s while turning at 1 rad/s.
VehicleTruth step_at(double t) {
  VehicleTruth v;
  v.t = t;
  v.pose = {20.0 * t, 0.0, 1.0 * t};
  v.vx = 20.0;
  v.distance = 20.0 * t;
  return v;
}

TEST(TruthHistory, ATimeInAnOlderStepIsPosedBetweenThatStepsEnds) {
  TruthHistory h;
  for (int i = 0; i <= 4; ++i) h.push(step_at(0.0025 * i));
  // 1 ms after the second step, two steps before the newest: 20 m/s × 3.5 ms (posed from the last two steps, it
  // would be clamped to 7.5 ms: 5 cm off).
  const VehicleTruth v = h.at(0.0035);
  EXPECT_DOUBLE_EQ(v.t, 0.0035);
  EXPECT_NEAR(v.pose.x, 0.070, 1e-12);
  EXPECT_NEAR(v.pose.yaw, 0.0035, 1e-12);
  EXPECT_NEAR(v.distance, 0.070, 1e-12);
  // On a step: that step.
  EXPECT_DOUBLE_EQ(h.at(0.005).pose.x, 0.1);
  // Before the oldest kept and after the newest: the ends.
  EXPECT_DOUBLE_EQ(h.at(-1.0).t, 0.0);
  EXPECT_DOUBLE_EQ(h.at(1.0).t, 0.01);
}

TEST(TruthHistory, TheYawTakesTheShorterWayRound) {
  VehicleTruth a = step_at(0.0), b = step_at(0.01);
  a.pose.yaw = std::numbers::pi - 0.1;
  b.pose.yaw = -std::numbers::pi + 0.1;  // 0.2 rad on, across ±π
  const VehicleTruth m = interpolate(a, b, 0.005);
  EXPECT_NEAR(std::abs(m.pose.yaw), std::numbers::pi, 1e-12);
}

TEST(TruthHistory, KeepsItsBound) {
  TruthHistory h(4);
  for (int i = 0; i < 10; ++i) h.push(step_at(0.0025 * i));
  EXPECT_EQ(h.size(), 4u);
  EXPECT_DOUBLE_EQ(h.at(0.0).t, 0.0025 * 6);  // the oldest kept
}

}  // namespace
}  // namespace fsd::sim
