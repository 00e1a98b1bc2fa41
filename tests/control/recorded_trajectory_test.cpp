// The lap-2 trajectory from recorded poses: closing the loop, smoothing a wobbly driven line, recentring on the
// mapped cones, the closed speed profile, and refusing laps that do not close.
#include <gtest/gtest.h>

#include <algorithm>
#include <numbers>
#include <random>
#include <tuple>

#include "control/planning/recorded_trajectory.hpp"
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

TEST(RecordedTrajectory, RecentringLeavesOutAnUncolouredConeOutsideTheBoundaryAndKeepsOneInside) {
  // The lane above (boundaries at y = ±1.8, the line 0.4 m left of centre), and two cones without a colour, as
  // the LiDAR alone maps a tyre or a post: one 2.2 m outside the left boundary at x = 21 (it bounds nothing: the
  // centre stays at y = 0 there), one 0.6 m inside the right boundary at x = 39 (it narrows the lane: the centre
  // there is half way between y = 1.8 and y = −1.2).
  Path open;
  for (int i = 0; i <= 100; ++i) open.points.push_back({Vec2(0.5 * i, 0.4), 0, 0, 0, 0});
  compute_geometry(open);
  std::vector<Cone> cones;
  auto add = [&cones](double x, double y, ConeColour colour) {
    Cone c;
    c.position = Vec3(x, y, 0);
    c.colour = colour;
    cones.push_back(c);
  };
  for (int i = -2; i <= 20; ++i) {
    add(3.0 * i, 1.8, ConeColour::Blue);
    add(3.0 * i, -1.8, ConeColour::Yellow);
  }
  add(21.0, 4.0, ConeColour::Unknown);
  add(39.0, -1.2, ConeColour::Unknown);
  recentre_on_cones(open, cones, ColourConvention{}, 4.0);
  for (const auto& q : open.points) {
    if (std::abs(q.p.x() - 21.0) < 1.0) {
      EXPECT_NEAR(q.p.y(), 0.0, 1e-9) << q.p.x();
    }
    if (std::abs(q.p.x() - 39.0) < 0.01) {
      EXPECT_NEAR(q.p.y(), 0.3, 1e-9) << q.p.x();
    }
  }
}

// Distance from p to the closed polyline through `v`.
double polyline_distance(const std::vector<Vec2>& v, const Vec2& p) {
  double best = 1e9;
  for (std::size_t i = 0; i < v.size(); ++i) {
    const Vec2 a = v[i], d = v[(i + 1) % v.size()] - a;
    const double t = std::clamp((p - a).dot(d) / d.squaredNorm(), 0.0, 1.0);
    best = std::min(best, (a + t * d - p).norm());
  }
  return best;
}

TEST(RecordedTrajectory, RecentringInABendTakesTheMiddleBetweenTheBoundaryLines) {
  // A ring lane (left boundary r = 8 m, right r = 12 m, driving anticlockwise) with cones 5 m apart on each: the
  // boundaries a driver sees are the chords between cones, 0.39 m and 0.26 m inside the circles at mid-chord.
  // The driven line runs 0.6 m wide of the ring's middle (1.2 m nearer one boundary line than the other).
  // Afterwards every point is as far from one boundary line as from the other within 0.2 m: the centre is taken
  // half way between each point of the left boundary and its closest point on the right one (the track's centre
  // line as the scorecard defines it), which is not an exact bisector where a boundary has a corner at a cone.
  const double pi = std::numbers::pi;
  std::vector<Vec2> inner, outer;
  std::vector<Cone> cones;
  for (const auto& [r, colour, out] :
       {std::tuple{8.0, ConeColour::Blue, &inner}, std::tuple{12.0, ConeColour::Yellow, &outer}}) {
    const int n = static_cast<int>(std::round(2 * pi * r / 5.0));
    for (int k = 0; k < n; ++k) {
      const Vec2 q = r * Vec2(std::cos(2 * pi * k / n), std::sin(2 * pi * k / n));
      out->push_back(q);
      Cone c;
      c.position = Vec3(q.x(), q.y(), 0);
      c.colour = colour;
      cones.push_back(c);
    }
  }
  Path p;
  p.closed = true;
  for (int i = 0; i < 400; ++i)
    p.points.push_back({10.6 * Vec2(std::cos(2 * pi * i / 400), std::sin(2 * pi * i / 400)), 0, 0, 0, 0});
  compute_geometry(p);
  recentre_on_cones(p, cones, ColourConvention{}, 4.0);
  for (const auto& q : p.points) {
    const double dl = polyline_distance(inner, q.p), dr = polyline_distance(outer, q.p);
    EXPECT_NEAR(dl, dr, 0.2) << q.p.transpose();
    EXPECT_NEAR(dl + dr, 4.0, 0.4);  // the lane is 4 m wide between the circles, less at mid-chord
    // Between the chords' middles (8 − 0.39 + 12 − 0.26) / 2 = 9.67 m and the circles' (10 m) from the centre.
    EXPECT_GT(q.p.norm(), 9.6);
    EXPECT_LT(q.p.norm(), 10.1);
  }
}

TEST(RecordedTrajectory, RecentringRoundACornerFollowsTheCentreLineNotTheNearestCones) {
  // A lane turning left by 90°: left boundary along y = 2 to its corner cone at (0, 2), then up x = 0; right
  // boundary along y = −2 to (4.2, −2), then up x = 4.2. Cones every 4 m (4.2 m round the outer corner). The
  // centre line (each left-boundary point's midpoint with its closest right-boundary point, sampled every 0.25 m
  // from the cones) runs along y = 0 to (0, 0): the corner cone's closest right point is (0, −2), 4 m away
  // against 4.2 m to (4.2, 2). The next sample, (0, 2.25), is 4.2 m from (4.2, 2.25) and 4.25 m from (0, −2): the
  // centre crosses the corner on the chord to (2.1, 2.25) and runs up x = 2.1. The line driven rounds the corner
  // wide: y = −0.5, an arc of radius 2 round (0.5, 1.5), x = 2.5. Afterwards every point lies on that centre line.
  std::vector<Cone> cones;
  auto cone = [&](double x, double y, ConeColour colour) {
    Cone c;
    c.position = Vec3(x, y, 0);
    c.colour = colour;
    cones.push_back(c);
  };
  for (double x = -24; x <= 0; x += 4) cone(x, 2, ConeColour::Blue);
  for (double y = 6; y <= 26; y += 4) cone(0, y, ConeColour::Blue);
  for (double x = -24; x <= 0; x += 4) cone(x, -2, ConeColour::Yellow);
  for (double y = -2; y <= 26; y += 4) cone(4.2, y, ConeColour::Yellow);
  Path p;
  for (double x = -16; x < 0.5; x += 0.1) p.points.push_back({Vec2(x, -0.5), 0, 0, 0, 0});
  for (double a = -std::numbers::pi / 2; a < 0; a += 0.05)
    p.points.push_back({Vec2(0.5, 1.5) + 2.0 * Vec2(std::cos(a), std::sin(a)), 0, 0, 0, 0});
  for (double y = 1.5; y <= 18; y += 0.1) p.points.push_back({Vec2(2.5, y), 0, 0, 0, 0});
  compute_geometry(p);
  auto centre_distance = [](const Vec2& q) {
    const Vec2 corner(2.1, 2.25);
    const double along = q.x() <= 0 ? std::abs(q.y()) : q.norm();
    const double up = q.y() >= corner.y() ? std::abs(q.x() - corner.x()) : (q - corner).norm();
    const double t = std::clamp(q.dot(corner) / corner.squaredNorm(), 0.0, 1.0);
    return std::min({along, up, (q - t * corner).norm()});
  };
  double before = 0;
  for (const auto& q : p.points) before = std::max(before, centre_distance(q.p));
  EXPECT_GT(before, 0.4);
  const double rms = recentre_on_cones(p, cones, ColourConvention{}, 4.0);
  EXPECT_GT(rms, 0.3);
  for (const auto& q : p.points) EXPECT_LT(centre_distance(q.p), 1e-6) << q.p.transpose();
}

TEST(RecordedTrajectory, RelocateMovesEachPoseByTheCorrectionOfItsInstant) {
  // A circle lap recorded by a pose drifting 2 m along +y over the lap (its end 2 m from its start), then the loop
  // closure's correction, growing with time as the drift did: the lap lies on the true circle again.
  RecordedTrajectory rec;
  const double r = 20.0, lap = 2 * std::numbers::pi * r, v = 5.0, T = lap / v;
  for (double t = 0; t <= T; t += 0.02) {
    const double a = v * t / r;
    rec.record(at(t, r * Vec2(std::cos(a), std::sin(a)) + Vec2(0, 2.0 * t / T)));
  }
  SpeedLimits lim;
  lim.mu = 1.0;
  lim.v_max = 30;
  const auto drifted = rec.build(0, T, {}, ColourConvention{}, SpeedProfile(lim));
  ASSERT_TRUE(drifted.path) << drifted.reason;
  double off = 0;  // the drifted lap's worst distance from the true circle
  for (const auto& q : drifted.path->points) off = std::max(off, std::abs(q.p.norm() - r));
  EXPECT_GT(off, 0.8);
  const double moved = rec.relocate([&](Stamp t) { return Pose2{0, -2.0 * t / T, 0}; });
  EXPECT_NEAR(moved, 2.0, 0.01);
  const auto res = rec.build(0, T, {}, ColourConvention{}, SpeedProfile(lim));
  ASSERT_TRUE(res.path) << res.reason;
  for (const auto& q : res.path->points) EXPECT_NEAR(q.p.norm(), r, 0.05);
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
  EXPECT_EQ(rec.size(), 4u);                                                     // 0, 0.3, 0.6, 0.9
}

}  // namespace
}  // namespace fsd

namespace fsd {
namespace {

std::vector<Cone> ring_of_cones(double radius, int n, ConeColour colour) {
  std::vector<Cone> out;
  for (int i = 0; i < n; ++i) {
    Cone c;
    const double a = 2 * std::numbers::pi * i / n;
    c.position = Vec3(radius * std::cos(a), radius * std::sin(a), 0);
    c.colour = colour;
    out.push_back(c);
  }
  return out;
}

TEST(RecordedTrajectory, TheMinimumCurvatureLineRunsTheRingAsWideAsTheBodyAllows) {
  // A ring track, counter-clockwise: inner (left, blue) cones at 8 m, outer (right, yellow) at 12 m, every 2 m
  // along the outer edge; lap 1 driven on the centre circle (10 m). The flattest line is the largest circle the body
  // fits: its outer front corner runs on √((R + w)² + f²), which must stay inside the outer cones' bases, so
  // R < √((12 − 0.12)² − 2.4²) − 0.7 = 10.93 m; the soft clearance (0.3 m) keeps it a little inside that.
  RecordedTrajectoryConfig cfg;
  cfg.line = "min_curvature";
  RecordedTrajectory rec(cfg);
  const double r = 10.0, v = 5.0, lap = 2 * std::numbers::pi * r;
  for (double t = 0; t <= lap / v; t += 0.02) {
    const double a = v * t / r;
    rec.record(at(t, r * Vec2(std::cos(a), std::sin(a))));
  }
  const int n_out = 38, n_in = 25;  // ≈ 2 m apart on each edge
  std::vector<Cone> cones = ring_of_cones(12.0, n_out, ConeColour::Yellow);
  for (const auto& c : ring_of_cones(8.0, n_in, ConeColour::Blue)) cones.push_back(c);
  SpeedLimits lim;
  lim.mu = 1.0;
  lim.v_max = 30;
  const auto res = rec.build(0, lap / v, cones, ColourConvention{}, SpeedProfile(lim));
  ASSERT_TRUE(res.path) << res.reason;
  const double body_limit = std::sqrt(std::pow(12.0 - 0.12, 2) - 2.4 * 2.4) - 0.7;
  double lo = 1e9, hi = 0;
  for (const auto& q : res.path->points) lo = std::min(lo, q.p.norm()), hi = std::max(hi, q.p.norm());
  EXPECT_LT(hi, body_limit);
  EXPECT_GT(lo, body_limit - 0.5);
  EXPECT_LT(hi - lo, 0.1) << "a circle";
  // Faster than the centre circle: √(μ g R) at the larger radius.
  for (const auto& q : res.path->points) EXPECT_GT(q.v, std::sqrt(9.81 * r) * 1.02);
  // On the centre line instead, it stays on the centre circle.
  cfg.line = "centre";
  RecordedTrajectory centre(cfg);
  for (double t = 0; t <= lap / v; t += 0.02) {
    const double a = v * t / r;
    centre.record(at(t, r * Vec2(std::cos(a), std::sin(a))));
  }
  const auto c = centre.build(0, lap / v, cones, ColourConvention{}, SpeedProfile(lim));
  ASSERT_TRUE(c.path) << c.reason;
  for (const auto& q : c.path->points) EXPECT_NEAR(q.p.norm(), r, 0.15);
}

}  // namespace
}  // namespace fsd
