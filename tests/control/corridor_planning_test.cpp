// Lap 1's planner on hand-made corridors that sit at the rules' limits, each judged by the simulator's own contact
// test (the car's rectangle as the virtual car draws it, against each cone's disc: drivers/sim/world/cone_geometry.hpp)
// and by the steering's reach, computed here from the path's points:
//   - a constant turn at the rules' 9 m outside diameter, 3 m lane, the car starting inside it;
//   - an S of two such hairpins with no straight between them;
//   - a lane closed by a row of cones: the plan ends before the row, with the stop it needs.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>

#include "control/planning/realtime_planner.hpp"
#include "drivers/sim/world/cone_geometry.hpp"

namespace fsd {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kConeRadius = 0.114;  // the simulator's small cone (228 mm base)

PathConfig path_config() {
  PathConfig c;
  c.body = {2.4, 0.5, 0.7};
  c.wheelbase = 1.53;
  c.max_steer = 0.5;
  return c;
}

SpeedLimits limits() {
  SpeedLimits l;
  l.mu = 0.72;
  l.v_max = 8.0;
  l.kappa_rate_max = 0.5;
  l.understeer = 0.0036;
  return l;
}

Cone cone(const Vec2& p, ConeColour c) {
  Cone k;
  k.position = Vec3(p.x(), p.y(), 0.0);
  k.colour = c;
  return k;
}

// Cones on an arc about `centre` from angle a0 to a1 (rad), at most `gap` apart.
void ring(std::vector<Cone>& out, const Vec2& centre, double r, double a0, double a1, double gap, ConeColour c) {
  const int n = std::max(1, static_cast<int>(std::ceil(std::abs(a1 - a0) * r / gap)));
  for (int i = 0; i <= n; ++i) {
    const double a = a0 + (a1 - a0) * i / n;
    out.push_back(cone(centre + r * Vec2(std::cos(a), std::sin(a)), c));
  }
}

// The least clearance of the simulator's rectangle along the path to any cone, every 2 cm, from `from` metres on.
double simulator_clearance(const Path& path, const std::vector<Cone>& cones, double from) {
  double least = 1e9;
  for (double s = from; s <= path.length(); s += 0.02) {
    const PathPoint q = sample(path, s);
    const Pose2 pose{q.p.x(), q.p.y(), q.yaw};
    const std::array<Vec2, 4> body{pose.transform({-0.5, -0.7}), pose.transform({2.4, -0.7}),
                                   pose.transform({2.4, 0.7}), pose.transform({-0.5, 0.7})};
    for (const auto& c : cones) {
      // Bisect the largest radius at which the disc still does not touch.
      const Vec2 p = c.position.head<2>();
      if ((p - pose.position()).norm() > 4.0) continue;
      double lo = 0.0, hi = 1.0;
      if (sim::polygon_touches_disc(body, p, kConeRadius)) {
        ADD_FAILURE() << "contact at s " << s << " with the cone at (" << p.x() << ", " << p.y() << ")";
        least = std::min(least, -1.0);
        continue;
      }
      if (!sim::polygon_touches_disc(body, p, kConeRadius + hi)) continue;
      for (int k = 0; k < 30; ++k) {
        const double mid = 0.5 * (lo + hi);
        (sim::polygon_touches_disc(body, p, kConeRadius + mid) ? hi : lo) = mid;
      }
      least = std::min(least, lo);
    }
  }
  return least;
}

// The steering angle the path asks for at its sharpest, from the circle through neighbouring points 0.5 m apart.
double sharpest_steer(const Path& path) {
  double k = 0;
  for (double s = 0.5; s + 0.5 <= path.length(); s += 0.1) {
    const Vec2 a = sample(path, s - 0.5).p, b = sample(path, s).p, c = sample(path, s + 0.5).p;
    const double area2 = std::abs((b - a).x() * (c - b).y() - (b - a).y() * (c - b).x());
    k = std::max(k, 2.0 * area2 / ((b - a).norm() * (c - b).norm() * (c - a).norm()));
  }
  return std::atan(1.53 * k);
}

VehicleState state_at(const Pose2& p, double v = 0.0) {
  VehicleState s;
  s.pose = p;
  s.vx = v;
  return s;
}

TEST(CorridorPlanning, AConstantTurnAtTheRulesTightestFromInsideIt) {
  // Outside diameter 9 m, inside 3 m: the lane's centre at 3 m; the car on it heading round counter-clockwise.
  std::vector<Cone> cones;
  ring(cones, Vec2::Zero(), 4.5, 0, 2 * kPi, 2.0, ConeColour::Yellow);  // outside: on the car's right
  ring(cones, Vec2::Zero(), 1.5, 0, 2 * kPi, 1.2, ConeColour::Blue);
  const RealtimePlanner planner({}, path_config(), ColourConvention{}, limits());
  const PlanResult r = planner.plan(cones, state_at({3.0, 0.0, kPi / 2}));
  ASSERT_TRUE(r.ok) << r.reason;
  EXPECT_GE(r.path.length(), 8.0) << "the plan goes round the turn, " << r.reason;
  // From a standstill on the lane's centre the car only just fits at the lock (an outer cone 48° round is 1 cm from
  // the nose's arc): no contact, and the speed there is the steering's crawl.
  EXPECT_GE(simulator_clearance(r.path, cones, 0.0), 0.0);
  // At the start the car must be at the lock itself: within a hair of it (1 %: a millimetre over the first metre).
  EXPECT_LE(sharpest_steer(r.path), 0.505);
}

TEST(CorridorPlanning, AnSOfTwoHairpinsAtTheRulesTightestWithNoStraightBetween) {
  // Left hairpin about (0, 3), then right hairpin about (0, 9): lane centre radius 3, lane 3 m; straights in and out.
  std::vector<Cone> cones;
  const ConeColour left = ConeColour::Blue, right = ConeColour::Yellow;
  for (double x = -12.0; x <= 0.0; x += 4.0) {
    cones.push_back(cone({x, 1.5}, left));
    cones.push_back(cone({x, -1.5}, right));
  }
  ring(cones, {0, 3}, 1.5, -kPi / 2, kPi / 2, 1.2, left);        // inside of the left hairpin
  ring(cones, {0, 3}, 4.5, -kPi / 2, kPi / 2, 1.8, right);       // its outside
  ring(cones, {0, 9}, 1.5, -kPi / 2, -3 * kPi / 2, 1.2, right);  // the right hairpin, round the other way
  ring(cones, {0, 9}, 4.5, -kPi / 2, -3 * kPi / 2, 1.8, left);
  for (double x = 0.0; x <= 12.0; x += 4.0) {
    cones.push_back(cone({x, 13.5}, left));
    cones.push_back(cone({x, 10.5}, right));
  }
  PlannerConfig pc;
  pc.range = 30;
  pc.walk.horizon = 45;
  const RealtimePlanner planner(pc, path_config(), ColourConvention{}, limits());
  const PlanResult r = planner.plan(cones, state_at({-8.0, 0.0, 0.0}, 4.0));
  ASSERT_TRUE(r.ok) << r.reason;
  EXPECT_FALSE(r.cut_short) << r.reason;
  // Through both hairpins: the end is past the second one's exit.
  EXPECT_GT(r.path.points.back().p.y(), 10.0);
  EXPECT_GE(simulator_clearance(r.path, cones, 1.0), 0.02);
  EXPECT_LE(sharpest_steer(r.path), 0.5);
}

TEST(CorridorPlanning, ALaneClosedByARowEndsBeforeItAndStopsThere) {
  std::vector<Cone> cones;
  for (double x = -4.0; x <= 20.0; x += 2.5) {
    cones.push_back(cone({x, 1.5}, ConeColour::Blue));
    cones.push_back(cone({x, -1.5}, ConeColour::Yellow));
  }
  for (double y = -1.0; y <= 1.01; y += 1.0) cones.push_back(cone({20.0, y}, ConeColour::Orange));
  SpeedLimits l = limits();
  l.v_max = 20.0;
  l.mu = 1.2;
  const RealtimePlanner planner({}, path_config(), ColourConvention{}, l);
  const PlanResult r = planner.plan(cones, state_at({0.0, 0.0, 0.0}, 8.0));
  ASSERT_TRUE(r.ok) << r.reason;
  const PathPoint end = r.path.points.back();
  // The nose stops short of the row's bases.
  EXPECT_LT(end.p.x() + 2.4, 20.0 - kConeRadius);
  EXPECT_GE(simulator_clearance(r.path, cones, 0.0), 0.0);
  EXPECT_NEAR(end.v, 0.0, 1e-9);
  // Every point can still stop before the end, a metre short, braking 0.3 s late at 8 m/s².
  for (const auto& q : r.path.points) {
    const double d = r.path.length() - q.s - 1.0;
    EXPECT_LE(q.v * q.v + 2 * 8.0 * 0.3 * q.v, std::max(0.0, 2 * 8.0 * d) + 1e-6) << "at s " << q.s;
  }
}

}  // namespace
}  // namespace fsd
