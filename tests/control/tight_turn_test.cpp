// The line through a tight turn, checked against the geometry of the car and the cones: the rules' tightest
// hairpin (9 m outside diameter, 3 m lane) built by hand, with the body swept along the line it gets.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "control/smoothing.hpp"
#include "control/tight_turn.hpp"

namespace fsd {
namespace {

constexpr double kPi = std::numbers::pi;

// A hairpin to the left around c: up x = c.x + rm from y = c.y − 12, half a circle of radius rm, back down; cones
// on rings r_in and r_out round the turn and along both straights every 3 m.
struct Hairpin {
  Vec2 c{0.0, 21.0};
  double r_in = 1.5, r_out = 4.5;
  std::vector<Vec2> cones;
  Path midline;  // the lane's centre line, smoothed like the planner's (5 m)

  explicit Hairpin(double start_y = 9.0, double outer = 4.5, double inner = 1.5) : r_in(inner), r_out(outer) {
    const double rm = 0.5 * (r_in + r_out);
    for (double y = c.y() - 12; y < c.y(); y += 3)
      for (double x : {r_in, r_out, -r_in, -r_out}) cones.push_back(c + Vec2(x, y - c.y()));
    for (int k = 0; k <= 4; ++k) cones.push_back(c + r_in * Vec2(std::cos(k * kPi / 4), std::sin(k * kPi / 4)));
    for (int k = 0; k <= 5; ++k) cones.push_back(c + r_out * Vec2(std::cos(k * kPi / 5), std::sin(k * kPi / 5)));
    Path raw;
    for (double y = start_y; y < c.y(); y += 0.25) raw.points.push_back({Vec2(c.x() + rm, y), 0, 0, 0, 0});
    for (double a = 0; a < kPi; a += 0.25 / rm)
      raw.points.push_back({c + rm * Vec2(std::cos(a), std::sin(a)), 0, 0, 0, 0});
    for (double y = c.y(); y > c.y() - 12; y -= 0.25) raw.points.push_back({Vec2(c.x() - rm, y), 0, 0, 0, 0});
    compute_geometry(raw);
    midline = smooth_path(raw, 0.25, 5.0);
  }
};

struct Sweep {
  double clearance = 1e9;  // least gap between the body and a cone's base (a cone is 0.24 m across)
  double kappa_max = 0;    // sharpest curvature along the line
};

// The body (0.5 m behind to 2.4 m ahead of the rear axle, 0.7 m to each side) carried along the line, tangent to
// it, against every cone.
Sweep sweep_body(const Path& path, const std::vector<Vec2>& cones) {
  Sweep s;
  for (const auto& q : path.points) {
    const Vec2 f(std::cos(q.yaw), std::sin(q.yaw)), l(-f.y(), f.x());
    for (const auto& c : cones) {
      const Vec2 d = c - q.p;
      const double x = d.dot(f), y = d.dot(l);
      const double dx = std::max({-0.5 - x, 0.0, x - 2.4}), dy = std::max({-0.7 - y, 0.0, y - 0.7});
      s.clearance = std::min(s.clearance, std::hypot(dx, dy) - 0.12);
    }
    s.kappa_max = std::max(s.kappa_max, std::abs(q.kappa));
  }
  return s;
}

TEST(TightTurn, TheRulesTightestHairpinGetsAnArcTheCarCanDriveInsideTheCones) {
  const Hairpin h;
  const TightTurnConfig cfg;  // wheelbase 1.53 m, lock 0.5 rad: the lock's radius is 2.80 m
  const double kappa_lock = std::tan(cfg.max_steer) / cfg.wheelbase;

  // The centre line does not fit: at its curvature the car cannot steer, or its body touches a cone.
  const Sweep before = sweep_body(h.midline, h.cones);
  EXPECT_TRUE(before.kappa_max > kappa_lock || before.clearance < 0)
      << "kappa " << before.kappa_max << " clearance " << before.clearance;

  Path line = h.midline;
  const auto turns = shape_tight_turns(line, h.cones, cfg);
  ASSERT_EQ(turns.size(), 1u);
  const auto turn = &turns.front();
  EXPECT_NEAR(turn->centre.x(), h.c.x(), 0.02);
  EXPECT_NEAR(turn->centre.y(), h.c.y(), 0.02);
  EXPECT_NEAR(turn->inner_radius, h.r_in, 0.02);
  EXPECT_NEAR(turn->outer_radius, h.r_out, 0.02);
  EXPECT_NEAR(turn->sweep, kPi, 0.1);
  // Hand-computed window: 1.53 / tan 0.5 · 1.02 = 2.857 m at least; √((4.5 − 0.17)² − 2.4²) − 0.7 = 2.904 m at most.
  EXPECT_GE(turn->radius, 2.856);
  EXPECT_LE(turn->radius, 2.905);

  const Sweep after = sweep_body(line, h.cones);
  EXPECT_LE(after.kappa_max, kappa_lock);
  EXPECT_GT(after.clearance, 0.0);
  // Through the middle of the turn the rear axle runs on the arc.
  for (const auto& q : line.points) {
    const Vec2 d = q.p - h.c;
    const double a = std::atan2(d.y(), d.x());
    if (a > 0.5 && a < kPi - 0.5) {
      EXPECT_NEAR(d.norm(), turn->radius, 0.02) << q.p.transpose();
    }
  }
  // It starts where the path started and ends back on the lane's centre line, heading down it.
  EXPECT_LT((line.points.front().p - h.midline.points.front().p).norm(), 0.05);
  EXPECT_LT(std::abs(line.points.back().p.x() - (h.c.x() - 3.0)), 0.05);
  EXPECT_NEAR(line.points.back().yaw, -kPi / 2, 0.05);
}

// Lap 1's speed through a shaped turn follows from the room the cones leave the rear axle's arc, hand-computed for
// three outer rings round the same 1.5 m inner ring (TightTurnConfig's defaults: K 0.0036 rad per m/s², half the
// room, 1.5–5 m/s). The inner limit is 1.5 + 0.17 + 0.7 = 2.37 m; the nose's, √((r_out − 0.17)² − 2.4²) − 0.7.
TEST(TightTurn, ATurnIsDrivenNoFasterThanItsRoomAllows) {
  const TightTurnConfig cfg;
  const auto shaped = [&](double r_out) {
    const Hairpin h(9.0, r_out);
    Path line = h.midline;
    const auto turns = shape_tight_turns(line, h.cones, cfg);
    EXPECT_EQ(turns.size(), 1u) << r_out;
    return turns.empty() ? TightTurn{} : turns.front();
  };
  // The rules' tightest: the arc at 2.8805 m (half-way from the lock's 2.857 m to the nose's 2.904 m) leaves
  // 0.0235 m: √(0.5 · 0.0235 · 1.53 / (2.8805 · 0.0036)) = 1.32 m/s, below the floor.
  const TightTurn tightest = shaped(4.5);
  EXPECT_NEAR(tightest.room, 0.0235, 0.005);
  EXPECT_NEAR(room_speed(tightest, cfg), cfg.v_min, 1e-9);
  // 4.65 m: the arc at the lock's authority, 2.912 m; the nose's limit 3.083 m leaves 0.171 m: 3.53 m/s.
  const TightTurn wider = shaped(4.65);
  EXPECT_NEAR(wider.room, 0.171, 0.005);
  EXPECT_NEAR(room_speed(wider, cfg), 3.53, 0.05);
  // A 4 m lane (5.5 m): the arc in the middle, 0.84 m either side: 7.5 m/s, capped at v_max.
  EXPECT_NEAR(room_speed(shaped(5.5), cfg), cfg.v_max, 1e-9);
  // Without an understeer gradient the room does not cap the speed.
  TightTurnConfig no_k = cfg;
  no_k.understeer = 0;
  EXPECT_NEAR(room_speed(tightest, no_k), cfg.v_max, 1e-9);
}

// A ring of cones is no perfect circle: an inner cone standing 0.6 m out of a 2.5 m ring into a 4 m lane. The
// line keeps to the middle of what the farthest inner cone and the nearest outer one leave (the body 0.64 m off
// that cone, 0.59 m off any); on the ring's mean radius it passed that cone at 0.45 m.
TEST(TightTurn, AnInnerConeStandingOutOfItsRingIsKeptClearOfAsTheOthers) {
  Hairpin h(9.0, 6.5, 2.5);
  for (auto& c : h.cones)
    if ((c - (h.c + Vec2(0.0, 2.5))).norm() < 1e-6) c = h.c + Vec2(0.0, 3.1);
  const TightTurnConfig cfg;
  Path line = h.midline;
  ASSERT_EQ(shape_tight_turns(line, h.cones, cfg).size(), 1u);
  const Sweep all = sweep_body(line, h.cones);
  EXPECT_GT(all.clearance, 0.5);
  const Sweep outlier = sweep_body(line, {h.c + Vec2(0.0, 3.1)});
  EXPECT_GT(outlier.clearance, 0.55);
}

TEST(TightTurn, ACarAlreadyInTheTurnGetsTheArcFromWhereItIs) {
  const Hairpin h;
  // The path starts 20° round (the car is in the turn).
  Path in_turn;
  for (const auto& q : h.midline.points)
    if (q.p.y() > h.c.y() + 1.0 || q.p.x() < h.c.x()) in_turn.points.push_back(q);
  compute_geometry(in_turn);
  const auto turns = shape_tight_turns(in_turn, h.cones, TightTurnConfig{});
  ASSERT_EQ(turns.size(), 1u);
  const auto turn = &turns.front();
  EXPECT_LT(turn->sweep, kPi - 0.3);  // it started ~20° round
  EXPECT_NEAR((in_turn.points.front().p - h.c).norm(), turn->radius, 0.02);
  EXPECT_GT(sweep_body(in_turn, h.cones).clearance, 0.0);
}

TEST(TightTurn, AHeldTurnKeepsTheCarOnItsArcToTheExitWhenTheConesAheadNoLongerFit) {
  const Hairpin h;
  Path line = h.midline;
  const auto first = shape_tight_turns(line, h.cones, TightTurnConfig{});
  ASSERT_EQ(first.size(), 1u);
  // Later, 135° round: the midline from there, and only the cones of the turn still ahead of the car (the planner
  // drops those behind; the exit straight's are beyond its view here): four, too few to fit the rings again.
  const double a0 = 0.75 * kPi;
  Path late;
  for (const auto& q : h.midline.points) {
    const Vec2 d = q.p - h.c;
    if (q.p.y() < h.c.y() - 0.01 && q.p.x() < h.c.x()) late.points.push_back(q);  // the straight out
    else if (q.p.y() >= h.c.y() - 0.01 && std::atan2(d.y(), d.x()) >= a0) late.points.push_back(q);
  }
  compute_geometry(late);
  std::vector<Vec2> ahead;
  for (const auto& c : h.cones) {
    const Vec2 d = c - h.c;
    if (c.y() >= h.c.y() - 0.01 && std::atan2(d.y(), d.x()) > a0 - 0.2) ahead.push_back(c);
  }
  Path plain = late;
  ASSERT_EQ(ahead.size(), 4u);
  EXPECT_TRUE(shape_tight_turns(plain, ahead, TightTurnConfig{}).empty()) << "the cones ahead alone fit no turn";

  Path held = late;
  const auto turns = shape_tight_turns(held, ahead, TightTurnConfig{}, &first.front());
  ASSERT_EQ(turns.size(), 1u);
  EXPECT_NEAR(turns.front().radius, first.front().radius, 1e-9);  // the rings fitted on the way in
  // Through the rest of the arc the rear axle stays on the held radius, and the body clears every cone.
  for (const auto& q : held.points) {
    const Vec2 d = q.p - h.c;
    const double a = std::atan2(d.y(), d.x());
    if (q.p.y() > h.c.y() + 0.3 && a > a0 + 0.3 && a < kPi - 0.4) {
      EXPECT_NEAR(d.norm(), first.front().radius, 0.05) << q.p.transpose();
    }
  }
  EXPECT_GT(sweep_body(held, h.cones).clearance, 0.0);
}

TEST(TightTurn, AHeldHairpinIsKeptAtItsEntryBesideItsOwnExitStraight) {
  // A hairpin's exit straight runs back beside its entry: a car still coming in stands "past" the exit along the
  // exit's direction. Round the turn's centre it has the whole turn still ahead, and the held turn is kept.
  const Hairpin h;
  Path line = h.midline;
  const auto first = shape_tight_turns(line, h.cones, TightTurnConfig{});
  ASSERT_EQ(first.size(), 1u);
  const TightTurn& held = first.front();
  ASSERT_NEAR(held.exit_direction.y(), -1.0, 0.05);  // down the exit straight
  // The path from the car on the entry straight, within the turn's reach, already farther down than the exit.
  const auto& pts = h.midline.points;
  const auto at = std::find_if(pts.begin(), pts.end(), [&](const PathPoint& q) {
    return q.p.x() > h.c.x() && q.p.y() < held.exit.y() - 0.1 && (q.p - h.c).norm() <= held.outer_radius + 1.0;
  });
  ASSERT_NE(at, pts.end()) << "exit " << held.exit.transpose();
  ASSERT_LE((held.exit - at->p).dot(held.exit_direction), 0.0);
  Path entry;
  entry.points.assign(at, pts.end());
  compute_geometry(entry);
  // Only the outer cones are in view (the inner ring hidden): nothing to fit the rings from afresh.
  std::vector<Vec2> outer_only;
  for (const auto& c : h.cones)
    if ((c - h.c).norm() > 4.0) outer_only.push_back(c);
  Path plain = entry;
  ASSERT_TRUE(shape_tight_turns(plain, outer_only, TightTurnConfig{}).empty());
  Path kept = entry;
  const auto turns = shape_tight_turns(kept, outer_only, TightTurnConfig{}, &held);
  ASSERT_EQ(turns.size(), 1u);
  EXPECT_NEAR(turns.front().radius, held.radius, 1e-9);
  EXPECT_GT(sweep_body(kept, h.cones).clearance, 0.0);
}

TEST(TightTurn, WideTurnsAndTurnsWithoutInnerConesAreLeftAlone) {
  // The same hairpin scaled to an 8 m lane radius: the centre line is drivable, nothing changes.
  Hairpin scaled;
  for (auto& c : scaled.cones) c = scaled.c + (c - scaled.c) * (8.0 / 3.0);
  for (auto& q : scaled.midline.points) q.p = scaled.c + (q.p - scaled.c) * (8.0 / 3.0);
  compute_geometry(scaled.midline);
  Path line = scaled.midline;
  EXPECT_TRUE(shape_tight_turns(line, scaled.cones, TightTurnConfig{}).empty());
  EXPECT_EQ(line.points.size(), scaled.midline.points.size());
  // Without cones inside the turn there is no centre to fit: left alone too.
  const Hairpin h;
  Path alone = h.midline;
  std::vector<Vec2> outer_only;
  for (const auto& c : h.cones)
    if ((c - h.c).norm() > 4.0) outer_only.push_back(c);
  EXPECT_TRUE(shape_tight_turns(alone, outer_only, TightTurnConfig{}).empty());
}

TEST(TightTurn, EveryHairpinOfAClosedLapIsShaped) {
  // A paperclip lap: two straights 30 m long joined by two of the rules' tightest hairpins (cone rings 1.5 and
  // 4.5 m round (0, 0) and (0, 30)), driven anticlockwise on its centre line smoothed like lap 2's (12 m).
  std::vector<Vec2> cones;
  for (double y = 0; y < 30; y += 3)
    for (double x : {1.5, 4.5, -1.5, -4.5}) cones.push_back({x, y});
  for (const double cy : {0.0, 30.0}) {
    const double a0 = cy > 0 ? 0.0 : kPi;
    for (int k = 1; k < 4; ++k)
      cones.push_back(Vec2(0, cy) + 1.5 * Vec2(std::cos(a0 + k * kPi / 4), std::sin(a0 + k * kPi / 4)));
    for (int k = 1; k < 5; ++k)
      cones.push_back(Vec2(0, cy) + 4.5 * Vec2(std::cos(a0 + k * kPi / 5), std::sin(a0 + k * kPi / 5)));
  }
  Path raw;
  raw.closed = true;
  for (double y = 0; y < 30; y += 0.25) raw.points.push_back({Vec2(3, y), 0, 0, 0, 0});
  for (double a = 0; a < kPi; a += 0.25 / 3)
    raw.points.push_back({Vec2(0, 30) + 3 * Vec2(std::cos(a), std::sin(a)), 0, 0, 0, 0});
  for (double y = 30; y > 0; y -= 0.25) raw.points.push_back({Vec2(-3, y), 0, 0, 0, 0});
  for (double a = kPi; a < 2 * kPi; a += 0.25 / 3)
    raw.points.push_back({3 * Vec2(std::cos(a), std::sin(a)), 0, 0, 0, 0});
  compute_geometry(raw);
  Path lap = smooth_path(raw, 0.25, 12.0);
  lap.closed = true;
  const TightTurnConfig cfg;
  const double kappa_lock = std::tan(cfg.max_steer) / cfg.wheelbase;
  const auto turns = shape_tight_turns_on_lap(lap, cones, cfg);
  ASSERT_EQ(turns.size(), 2u);
  EXPECT_TRUE(lap.closed);
  // Each turn is the right one (centre, rings), and the stretch it rebuilt lies on the lap around its centre.
  for (const auto& turn : turns) {
    const Vec2 centre(0, turn.centre.y() > 15 ? 30 : 0);
    EXPECT_LT((turn.centre - centre).norm(), 0.1);
    EXPECT_NEAR(turn.inner_radius, 1.5, 0.05);
    EXPECT_NEAR(turn.outer_radius, 4.5, 0.05);
    ASSERT_LT(turn.s_begin, turn.s_end);
    const Vec2 mid = sample(lap, 0.5 * (turn.s_begin + turn.s_end)).p;
    EXPECT_NEAR((mid - centre).norm(), turn.radius, 0.3);
  }
  const Sweep after = sweep_body(lap, cones);
  EXPECT_GT(after.clearance, 0.0);
  EXPECT_LE(after.kappa_max, kappa_lock);
  // Half way along each straight the line is back on the lane's centre, and the loop is still one lap long.
  EXPECT_LT(project(lap, Vec2(3, 15))->distance(), 0.1);
  EXPECT_LT(project(lap, Vec2(-3, 15))->distance(), 0.1);
  EXPECT_NEAR(lap.length(), 60 + 2 * kPi * 2.9, 1.5);
}

TEST(TightTurn, AHairpinIntoABendTheOtherWayRejoinsWithinTheLock) {
  // The rules' hairpin, then 3 m down its exit straight a right-hand bend (lane radius 4 m round (−7, 18)) onto a
  // straight heading −x: an S out of a hairpin (epfl_autoX's). Rejoined 5 m after the hairpin, the straight out
  // of the arc meets the path in the bend at an angle that its rounding turns into a bend of 0.68 1/m, and the
  // body clips the bend's inner cone; the line must stay within the lock all through, the body clear of the cones.
  const Hairpin h;
  const Vec2 bend(-7.0, 18.0);
  std::vector<Vec2> cones;
  for (const auto& c : h.cones)
    if (c.x() > 0 || c.y() >= bend.y()) cones.push_back(c);
  for (int k = 0; k <= 3; ++k) cones.push_back(bend + 2.5 * Vec2(std::cos(-k * kPi / 6), std::sin(-k * kPi / 6)));
  for (int k = 0; k <= 5; ++k) cones.push_back(bend + 5.5 * Vec2(std::cos(-k * kPi / 10), std::sin(-k * kPi / 10)));
  for (double x = -10; x > -30; x -= 3)
    for (const double y : {bend.y() - 2.5, bend.y() - 5.5}) cones.push_back({x, y});
  Path raw;
  const double rm = 3.0;
  for (double y = 9; y < h.c.y(); y += 0.25) raw.points.push_back({Vec2(rm, y), 0, 0, 0, 0});
  for (double a = 0; a < kPi; a += 0.25 / rm)
    raw.points.push_back({h.c + rm * Vec2(std::cos(a), std::sin(a)), 0, 0, 0, 0});
  for (double y = h.c.y(); y > bend.y(); y -= 0.25) raw.points.push_back({Vec2(-rm, y), 0, 0, 0, 0});
  for (double a = 0; a > -kPi / 2; a -= 0.25 / 4.0)
    raw.points.push_back({bend + 4.0 * Vec2(std::cos(a), std::sin(a)), 0, 0, 0, 0});
  for (double x = bend.x(); x > -30; x -= 0.25) raw.points.push_back({Vec2(x, bend.y() - 4.0), 0, 0, 0, 0});
  compute_geometry(raw);
  Path line = smooth_path(raw, 0.25, 5.0);
  const TightTurnConfig cfg;
  const double kappa_lock = std::tan(cfg.max_steer) / cfg.wheelbase;
  ASSERT_FALSE(shape_tight_turns(line, cones, cfg).empty());
  const Sweep after = sweep_body(line, cones);
  EXPECT_LE(after.kappa_max, kappa_lock);
  EXPECT_GT(after.clearance, 0.0);
  // It ends on the straight out of the bend.
  EXPECT_NEAR(line.points.back().p.y(), bend.y() - 4.0, 0.05);
}

}  // namespace
}  // namespace fsd
