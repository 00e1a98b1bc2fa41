// The lap-2 trajectory from recorded poses: closing the loop, smoothing a wobbly driven line, recentring on the
// mapped cones, the closed speed profile, and refusing laps that do not close.
#include <gtest/gtest.h>

#include <numbers>
#include <random>

#include "control/recorded_trajectory.hpp"
#include "tests/control/track_truth.hpp"

namespace fsd {
namespace {

VehicleState at(Stamp t, const Vec2& p) {
  VehicleState s;
  s.stamp = t;
  s.pose = {p.x(), p.y(), 0};
  return s;
}

TEST(RecordedTrajectory, ClosesAWobblyCircleOntoItsRadius) {
  // Driven circle of radius 20 m with a 0.15 m lateral wobble of 5 m wavelength, one lap at 5 m/s.
  RecordedTrajectory rec;
  const double r = 20.0, lap = 2 * std::numbers::pi * r, v = 5.0;
  for (double t = 0; t <= lap / v; t += 0.02) {
    const double a = v * t / r;
    const double wobble = 0.15 * std::sin(2 * std::numbers::pi * v * t / 5.0);
    rec.record(at(t, (r + wobble) * Vec2(std::cos(a), std::sin(a))));
  }
  SpeedLimits lim;
  lim.mu = 1.0;
  lim.v_max = 30;
  const auto res = rec.build(0, lap / v, {}, ColourConvention{}, SpeedProfile(lim));
  ASSERT_TRUE(res.path) << res.reason;
  EXPECT_TRUE(res.path->closed);
  EXPECT_LT(res.closure_gap, 0.5);
  double max_dr = 0;
  for (const auto& q : res.path->points) max_dr = std::max(max_dr, std::abs(q.p.norm() - r));
  EXPECT_LT(max_dr, 0.06);  // the wobble (0.15 m) is smoothed away
  // Speed at every waypoint: √(μ g r) = 14 m/s on the whole circle, within 10 % (what is left of the wobble,
  // and the step where the driven lap's end meets its start).
  for (const auto& q : res.path->points) EXPECT_NEAR(q.v, std::sqrt(9.81 * r), 1.4);
}

TEST(RecordedTrajectory, RecentringPullsTheLineToTheMiddleOfTheCones) {
  // Straight lane along +x between cones at y = +1.8 (left, blue) and y = −1.8 (right, yellow), every 3 m,
  // closed into a long stadium so that the lap closes; the driven line runs 0.4 m left of centre.
  Path p;
  p.closed = true;
  for (int i = 0; i <= 100; ++i) p.points.push_back({Vec2(0.5 * i, 0.4), 0, 0, 0, 0});
  compute_geometry(p);
  std::vector<Cone> cones;
  for (int i = -2; i <= 20; ++i) {
    Cone l, r;
    l.position = Vec3(3.0 * i, 1.8, 0);
    l.colour = ConeColour::Blue;
    r.position = Vec3(3.0 * i, -1.8, 0);
    r.colour = ConeColour::Yellow;
    cones.push_back(l);
    cones.push_back(r);
  }
  Path open = p;
  open.closed = false;
  compute_geometry(open);
  const double rms = recentre_on_cones(open, cones, ColourConvention{}, 4.0);
  EXPECT_NEAR(rms, 0.4, 1e-9);
  for (const auto& q : open.points) EXPECT_NEAR(q.p.y(), 0.0, 1e-9);
}

TEST(RecordedTrajectory, ALapThatDoesNotCloseIsRefused) {
  RecordedTrajectory rec;
  for (int i = 0; i < 300; ++i) rec.record(at(0.1 * i, Vec2(0.5 * i, 0)));
  const auto res = rec.build(0, 100, {}, ColourConvention{}, SpeedProfile{});
  EXPECT_FALSE(res.path);
  EXPECT_NE(res.reason.find("does not close"), std::string::npos);
  EXPECT_FALSE(RecordedTrajectory{}.build(0, 1, {}, ColourConvention{}, SpeedProfile{}).path);
}

TEST(RecordedTrajectory, KeepsOnePosePerSpacing) {
  RecordedTrajectory rec;
  for (int i = 0; i < 1000; ++i) rec.record(at(0.001 * i, Vec2(0.001 * i, 0)));  // 1 m in 1 mm steps
  EXPECT_EQ(rec.size(), 4u);  // 0, 0.3, 0.6, 0.9
}

}  // namespace
}  // namespace fsd
