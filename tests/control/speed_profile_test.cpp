// Speed profile against hand-computed values: steady cornering speed √(μgR), braking v² = v_c² + 2·a·d before a
// tight corner, traction-limited acceleration from rest, the power limit, and a periodic lap.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "control/planning/speed_profile.hpp"
#include "tests/control/path_helpers.hpp"

namespace fsd {
namespace {

SpeedLimits limits(double mu, double accel, double brake, double vmax) {
  SpeedLimits l;
  l.mu = mu;
  l.a_accel_max = accel;
  l.a_brake_max = brake;
  l.v_max = vmax;
  return l;
}

TEST(SpeedProfile, CircleAtTheFrictionLimit) {
  Path p = test::circle_path({0, 0}, 20.0, 400);
  SpeedProfile(limits(0.8, 5, 8, 30)).apply(p, 0, 0);
  const double expected = std::sqrt(0.8 * 9.81 * 20.0);  // 12.53 m/s
  for (const auto& q : p.points) EXPECT_NEAR(q.v, expected, 1e-6);
  EXPECT_NEAR(travel_time(p), p.length() / expected, 1e-6);
}

TEST(SpeedProfile, CircleCappedByVmax) {
  Path p = test::circle_path({0, 0}, 20.0, 400);
  SpeedProfile(limits(0.8, 5, 8, 10)).apply(p, 0, 0);
  for (const auto& q : p.points) EXPECT_NEAR(q.v, 10.0, 1e-12);
}

TEST(SpeedProfile, BrakingBeforeATightCorner) {
  // 60 m straight along +x, then a left arc of radius 5 m (quarter circle), points every 0.1 m.
  Path p;
  const double ds = 0.1, r = 5.0;
  for (int i = 0; i <= 600; ++i) p.points.push_back({Vec2(i * ds, 0), 0, 0, 0, 0});
  for (int i = 1; i <= 78; ++i) {
    const double a = i * ds / r;
    p.points.push_back({Vec2(60 + r * std::sin(a), r - r * std::cos(a)), 0, 0, 0, 0});
  }
  compute_geometry(p);
  const double mu = 1.2, brake = 6.0;  // braking below μg, so the brakes limit, not the tyres
  SpeedProfile(limits(mu, 4, brake, 25)).apply(p, 25, 100);
  const double vc = std::sqrt(mu * 9.81 * r);  // 7.67 m/s
  for (int i = 0; i <= 580; ++i) {             // from 2 m before the arc backwards
    const double d = 60.0 - i * ds;
    const double expected = std::min(25.0, std::sqrt(vc * vc + 2 * brake * d));
    EXPECT_NEAR(p.points[static_cast<std::size_t>(i)].v, expected, 0.08) << "d = " << d;
  }
  for (std::size_t i = 610; i < p.points.size() - 2; ++i) EXPECT_NEAR(p.points[i].v, vc, 1e-3);
}

TEST(SpeedProfile, AccelerationFromRestAndPowerLimit) {
  Path p = test::straight_path({0, 0}, 0.0, 100.0, 0.05);
  SpeedProfile(limits(1.5, 4.0, 8, 40)).apply(p, 0, 40);
  for (const auto& q : p.points) EXPECT_NEAR(q.v, std::sqrt(2 * 4.0 * q.s), 1e-6);  // v² = 2·a·s

  // With 20 kW on 250 kg the traction limit of 4 m/s² holds up to v = P/(m·a) = 20 m/s, then a = P/(m·v):
  // the kinetic energy grows by at most P·dt = P·ds/v, i.e. d(v²)/ds ≤ 2P/(m·v).
  SpeedLimits l = limits(1.5, 4.0, 8, 40);
  l.power_max = 20000;
  l.mass = 250;
  Path q = test::straight_path({0, 0}, 0.0, 200.0, 0.05);
  SpeedProfile(l).apply(q, 0, 40);
  for (std::size_t i = 1; i < q.points.size(); ++i) {
    const double v = q.points[i - 1].v;
    const double a_allowed = std::min(4.0, 20000.0 / (250.0 * std::max(v, 0.5)));
    const double dv2 = q.points[i].v * q.points[i].v - v * v;
    EXPECT_LE(dv2, 2 * a_allowed * 0.05 + 1e-9);
  }
  // Traction-limited to 20 m/s at s = 50 m, then constant power: d(v³)/ds = 3P/m, so at 200 m
  // v = (20³ + 3·80·150)^(1/3) = 35.30 m/s, short of the traction-only √(2·4·200) = 40.
  EXPECT_NEAR(q.points.back().v, std::cbrt(8000.0 + 240.0 * 150.0), 0.1);
}

TEST(SpeedProfile, FrictionCircleLeavesNoBrakingAtTheCorneringLimit) {
  SpeedLimits l = limits(1.0, 5, 8, 30);
  l.traction_ellipse = false;
  const SpeedProfile sp(l);
  const double k = 0.1;
  const double v = std::sqrt(9.81 / k);
  EXPECT_NEAR(sp.max_deceleration(v, k), 0.0, 1e-6);
  EXPECT_NEAR(sp.max_acceleration(v, k), 0.0, 1e-6);
  // At half the cornering speed a quarter of the grip goes sideways: the circle leaves 9.81·√(1 − 1/16) = 9.498,
  // capped by the motor's 5 and the brakes' 8.
  EXPECT_NEAR(sp.max_acceleration(0.5 * v, k), 5.0, 1e-9);
  EXPECT_NEAR(sp.max_deceleration(0.5 * v, k), std::min(8.0, 9.81 * std::sqrt(1 - 0.0625)), 1e-9);
}

TEST(SpeedProfile, TractionShrinksWithCorneringOnAnEllipse) {
  // Rear-wheel drive: the traction limit itself shrinks with the lateral share, 5·√(1 − (a_y/μg)²). At half the
  // cornering speed on κ = 0.1 (a_y = μg/4): 5·√(15/16) = 4.841 m/s² where the circle gave the full 5; at 80 % of
  // the grip sideways (v = √(0.8·9.81/0.1) = 8.859 m/s): 5·0.6 = 3 (the circle: min(5, 9.81·0.6 = 5.886) = 5).
  // Braking is the circle's either way (all four tyres brake).
  const SpeedProfile sp(limits(1.0, 5, 8, 30));
  const double k = 0.1;
  const double v = std::sqrt(9.81 / k);
  EXPECT_NEAR(sp.max_acceleration(0.5 * v, k), 5.0 * std::sqrt(15.0 / 16.0), 1e-9);
  EXPECT_NEAR(sp.max_acceleration(std::sqrt(0.8 * 9.81 / k), k), 3.0, 1e-9);
  EXPECT_NEAR(sp.max_acceleration(v, k), 0.0, 1e-6);
  EXPECT_NEAR(sp.max_acceleration(20.0, 0.0), 5.0, 1e-12);  // straight: the motor's limit
  EXPECT_NEAR(sp.max_deceleration(0.5 * v, k), std::min(8.0, 9.81 * std::sqrt(1 - 0.0625)), 1e-9);
}

TEST(SpeedProfile, SteeringRateCapsTheSpeedThroughAnSBend) {
  // Straight, then the curvature runs linearly from +0.2 to -0.2 1/m over 4 m (an S-bend's flick), then a
  // straight again: points every 0.05 m built by integrating the heading.
  Path p;
  Vec2 q(0, 0);
  double yaw = 0;
  const double ds = 0.05;
  auto kappa_at = [](double s) {
    if (s < 30.0) return 0.0;
    if (s < 32.0) return 0.1 * (s - 30.0);        // into the left bend
    if (s < 36.0) return 0.2 - 0.1 * (s - 32.0);  // the flick: dκ/ds = -0.1 1/m²
    if (s < 38.0) return -0.2 + 0.1 * (s - 36.0);
    return 0.0;
  };
  for (int i = 0; i <= 1400; ++i) {
    p.points.push_back({q, 0, 0, 0, 0});
    yaw += kappa_at(i * ds) * ds;
    q += ds * Vec2(std::cos(yaw), std::sin(yaw));
  }
  compute_geometry(p);
  SpeedLimits l = limits(1.2, 6, 8, 30);
  l.kappa_rate_max = 0.5;  // 1/(m·s)
  l.kappa_rate_window = 4.0;
  SpeedProfile(l).apply(p, 30, 30);
  // At the flick's middle (s = 34) the window 32…36 sees Δκ = -0.4 over 4 m: v ≤ 0.5 / 0.1 = 5 m/s, far below
  // the friction limit there (κ = 0: none) and at its ends (√(1.2·9.81/0.2) = 7.67 m/s).
  const PathPoint mid = sample(p, 34.0);
  EXPECT_NEAR(mid.v, 5.0, 0.15);
  // Off: the friction circle alone allows 7.67 m/s at the bend's peaks and more between them.
  l.kappa_rate_max = 0;
  SpeedProfile(l).apply(p, 30, 30);
  EXPECT_GT(sample(p, 34.0).v, 7.6);
  // On a constant-radius circle the rate limit never binds.
  Path c = test::circle_path({0, 0}, 20.0, 400);
  SpeedLimits lc = limits(0.8, 5, 8, 30);
  lc.kappa_rate_max = 0.5;
  SpeedProfile(lc).apply(c, 0, 0);
  for (const auto& pt : c.points) EXPECT_NEAR(pt.v, std::sqrt(0.8 * 9.81 * 20.0), 1e-6);
}

TEST(SpeedProfile, ClosedLapIsPeriodic) {
  // A stadium: two straights of 50 m joined by half circles of 10 m.
  Path p;
  p.closed = true;
  const double r = 10, ds = 0.25;
  for (double s = 0; s < 50; s += ds) p.points.push_back({Vec2(s, -r), 0, 0, 0, 0});
  for (double a = -std::numbers::pi / 2; a < std::numbers::pi / 2; a += ds / r)
    p.points.push_back({Vec2(50 + r * std::cos(a), r * std::sin(a)), 0, 0, 0, 0});
  for (double s = 50; s > 0; s -= ds) p.points.push_back({Vec2(s, r), 0, 0, 0, 0});
  for (double a = std::numbers::pi / 2; a < 3 * std::numbers::pi / 2; a += ds / r)
    p.points.push_back({Vec2(r * std::cos(a), r * std::sin(a)), 0, 0, 0, 0});
  compute_geometry(p);
  const double mu = 1.0, brake = 5.0, accel = 3.0;
  SpeedProfile(limits(mu, accel, brake, 30)).apply(p, 0, 0);
  const double vc = std::sqrt(mu * 9.81 * r);
  // Middle of a straight: the lower of accelerating from the corner and braking into the next.
  double vmax_straight = 0;
  for (const auto& q : p.points)
    if (std::abs(q.p.y() + r) < 1e-9) vmax_straight = std::max(vmax_straight, q.v);
  // Accelerating at 3 for d1 and braking at 5 for d2 with d1 + d2 = 50: v² = vc² + 6·d1 = vc² + 10·d2.
  const double d1 = 50.0 * 10.0 / 16.0;
  EXPECT_NEAR(vmax_straight, std::sqrt(vc * vc + 2 * accel * d1), 0.1);
  // Continuity across the seam.
  EXPECT_NEAR(p.points.front().v, p.points.back().v, 0.05);
}

TEST(SpeedProfile, AZoneCapsItsStretchAndThePassesBlendIntoIt) {
  // 100 m straight, points every 0.1 m, zone [40, 60] m at 5 m/s; braking 8, traction 5 (μ 1.2: grip is not
  // the limit on a straight). 10 m before the zone: v² = 5² + 2·8·10 → 13.60 m/s; 10 m after: 5² + 2·5·10 → 11.18;
  // at the start, 40 m before it: 5² + 2·8·40 → 25.79.
  Path p;
  for (double s = 0; s <= 100.0 + 1e-9; s += 0.1) p.points.push_back({Vec2(s, 0), 0, 0, 0, 0});
  compute_geometry(p);
  const SpeedProfile profile(limits(1.2, 5, 8, 30));
  profile.apply(p, 30, 30, {{39.95, 60.05, 5.0}});  // the points from 40 to 60 m
  auto v_at = [&](double s) { return p.points[static_cast<std::size_t>(std::lround(s / 0.1))].v; };
  EXPECT_NEAR(v_at(50), 5.0, 1e-9);
  EXPECT_NEAR(v_at(40), 5.0, 1e-9);
  EXPECT_NEAR(v_at(30), std::sqrt(25.0 + 2 * 8 * 10), 1e-6);
  EXPECT_NEAR(v_at(70), std::sqrt(25.0 + 2 * 5 * 10), 1e-6);
  EXPECT_NEAR(v_at(0), std::sqrt(25.0 + 2 * 8 * 40), 1e-6);  // the start speed (30) is out of reach

  // On a lap a zone may wrap over the start: [95, 5] on a 100 m loop (a circle of radius 100/2π, far from the
  // friction limit at 6 m/s: √(1.2·9.81·15.9) = 13.7 m/s).
  Path lap = test::circle_path({0, 0}, 100.0 / (2 * std::numbers::pi), 1000);
  profile.apply(lap, 0, 0, {{95, 5, 6.0}});
  const double vc = std::sqrt(1.2 * 9.81 * 100.0 / (2 * std::numbers::pi));
  for (const auto& q : lap.points) {
    if (q.s <= 5 || q.s >= 95) {
      EXPECT_NEAR(q.v, 6.0, 1e-9) << q.s;
    }
    if (q.s > 40 && q.s < 60) {
      EXPECT_NEAR(q.v, vc, 1e-6) << q.s;  // half a lap away: the circle's own limit
    }
  }
}

}  // namespace
}  // namespace fsd
