// The scorecard's "odometry" section against hand-computed figures: a scale error shows as drift per distance, a
// constant offset or a rotated start frame does not drift, and the pose pairs are thinned by distance.
#include "daemon/scoring/odometry_score.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include <nlohmann/json.hpp>

namespace fsd {
namespace {

// A straight 100 m along x at 0.5 m steps, the estimate from `estimate_of`.
template <class F>
std::vector<PosePair> straight(F estimate_of) {
  std::vector<PosePair> t;
  for (int i = 0; i <= 200; ++i) {
    const Pose2 truth{0.5 * i, 0.0, 0.0};
    t.push_back({truth, estimate_of(truth)});
  }
  return t;
}

TEST(OdometryScore, AOnePercentScaleErrorIsOnePercentDriftEverywhere) {
  const auto d = drift_of(straight([](const Pose2& p) { return Pose2{1.01 * p.x, 0.0, 0.0}; }));
  EXPECT_NEAR(d.distance_m, 100.0, 1e-9);
  EXPECT_NEAR(d.end_error_m, 1.0, 1e-9);
  EXPECT_NEAR(d.end_pct, 1.0, 1e-9);
  EXPECT_NEAR(d.segment_pct, 1.0, 1e-9);
  EXPECT_EQ(d.segments, 101);  // starts at 0, 0.5, ..., 50 m
}

TEST(OdometryScore, AnOffsetOrARotatedFrameIsAnEndErrorButNoDrift) {
  const auto shifted = drift_of(straight([](const Pose2& p) { return Pose2{p.x + 0.3, p.y - 0.4, 0.0}; }));
  EXPECT_NEAR(shifted.end_error_m, 0.5, 1e-9);
  EXPECT_NEAR(shifted.segment_pct, 0.0, 1e-9);
  // The same path seen from a frame turned by 30° about the start: relative motions are the same.
  const Pose2 frame{2.0, -1.0, std::numbers::pi / 6};
  const auto turned = drift_of(straight([&](const Pose2& p) { return frame * p; }));
  EXPECT_NEAR(turned.segment_pct, 0.0, 1e-9);
  EXPECT_GT(turned.end_error_m, 40.0);
}

TEST(OdometryScore, AHeadingErrorAtTheStartOfASegmentIsLateralDrift) {
  // Heading off by 0.01 rad from the start: after L metres the estimate is L·sin(0.01) to the side.
  const auto d = drift_of(straight([](const Pose2& p) {
    return Pose2{p.x * std::cos(0.01), p.x * std::sin(0.01), 0.01};
  }));
  EXPECT_NEAR(d.end_error_m, 100.0 * 2.0 * std::sin(0.005), 1e-9);
  // Each segment starts with the estimate already turned by 0.01: relative motion is exact, no drift.
  EXPECT_NEAR(d.segment_pct, 0.0, 1e-9);
}

TEST(OdometryScore, ShorterThanASegmentHasNoSegmentFigure) {
  std::vector<PosePair> t{{{0, 0, 0}, {0, 0, 0}}, {{10, 0, 0}, {10.2, 0, 0}}};
  const auto d = drift_of(t);
  EXPECT_EQ(d.segments, 0);
  EXPECT_EQ(d.segment_pct, 0.0);
  EXPECT_NEAR(d.end_pct, 2.0, 1e-9);
}

TEST(OdometryScore, PairsAreThinnedByDistanceAndTheEndIsExact) {
  OdometryScore score(0.5);
  // 100 m in 1 mm steps with a 2 % scale error: 100 k scans, kept as ~200 pairs; the end-point is the last scan's.
  for (int i = 0; i <= 100000; ++i) score.add_lidar({1e-3 * i, 0, 0}, {1.02e-3 * i, 0, 0});
  score.add_state({0, 0, 0}, {0.3, 0.4, 0});
  score.add_state({1, 0, 0}, {1, 0, 0});
  const auto j = score.to_json("lidar_odometry");
  EXPECT_EQ(j["source"], "lidar_odometry");
  EXPECT_NEAR(j["drift_pct"].get<double>(), 2.0, 1e-3);
  EXPECT_NEAR(j["lidar"]["end_error_m"].get<double>(), 2.0, 1e-3);
  EXPECT_NEAR(j["lidar"]["segment_drift_pct"].get<double>(), 2.0, 0.01);
  EXPECT_LE(j["lidar"]["segments"].get<int>(), 110);
  EXPECT_EQ(j["lidar"]["scans"], 100001);
  EXPECT_NEAR(j["ate_m"].get<double>(), std::sqrt(0.25 / 2), 1e-4);  // RMS of 0.5 and 0
  EXPECT_NEAR(j["ate_max_m"].get<double>(), 0.5, 1e-9);
  EXPECT_FALSE(OdometryScore().to_json("truth").contains("lidar"));
}

// The heading error: 2° on one state, none on the other (RMS √2°), and across ±π it is the short way round.
TEST(OdometryScore, HeadingErrorIsTheShortWayRound) {
  OdometryScore score;
  const double deg = std::numbers::pi / 180;
  score.add_state({0, 0, std::numbers::pi - 1 * deg}, {0, 0, -std::numbers::pi + 1 * deg});
  score.add_state({1, 0, 0.3}, {1, 0, 0.3});
  const auto j = score.to_json("fused");
  EXPECT_NEAR(j["yaw_max_deg"].get<double>(), 2.0, 1e-3);
  EXPECT_NEAR(j["yaw_rms_deg"].get<double>(), std::sqrt(2.0), 1e-3);
}

}  // namespace
}  // namespace fsd
