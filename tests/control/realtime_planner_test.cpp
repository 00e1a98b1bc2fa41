// Lap-1 real-time planning on every shared trackdrive/autocross layout. The car is put on the true centre line
// (rung midpoints of tests/control/track_truth.hpp) facing along the track and sees only the true cones up to
// 15 m ahead, as the first lap's perception would; the planned path must stay near the true centre and clear
// of every true cone. Then again with a fifth of the cones taken off the track, with every colour unknown, and
// with a tenth of the colours swapped;
// there the near field (the first 8 m, what the car drives before the next plans) is checked.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <optional>
#include <random>

#include "control/planning/realtime_planner.hpp"
#include "tests/control/track_truth.hpp"

namespace fsd {
namespace {

using test::TrackTruth;

enum class Variant { AllCones, FifthRemoved, ColourBlind, WrongColours };

// The track as the test presents it: a fifth of the cones taken away once (a seeded draw), or colours hidden.
Track variant_of(Track track, Variant v) {
  if (v == Variant::FifthRemoved) {
    std::mt19937 rng(7);
    std::shuffle(track.cones.begin(), track.cones.end(), rng);
    track.cones.resize(track.cones.size() - track.cones.size() / 5);
  }
  if (v == Variant::ColourBlind)
    for (auto& c : track.cones) c.colour = ConeColour::Unknown;
  if (v == Variant::WrongColours) {  // one cone in ten gets the other boundary's colour (a seeded draw)
    std::mt19937 rng(11);
    std::bernoulli_distribution swap(0.1);
    for (auto& c : track.cones) {
      if (!swap(rng)) continue;
      if (c.colour == track.convention.left)
        c.colour = track.convention.right;
      else if (c.colour == track.convention.right)
        c.colour = track.convention.left;
    }
  }
  return track;
}

// The car on the centre line facing along it: from the nearest rung midpoint behind to the nearest ahead (a diagonal
// rung's own heading can point 15° off the track, at a boundary cone a nose ahead: no car drives so). It stands (a car
// in motion brings its own curvature, and the rungs' is too rough to give it one its steering could have had).
struct OnCentre {
  double heading, kappa;
};
OnCentre on_centre(const TrackTruth& truth, const test::Rung& at) {
  const Vec2 h(std::cos(at.heading), std::sin(at.heading));
  std::optional<Vec2> ahead, behind;
  for (const auto& r : truth.rungs()) {
    const Vec2 d = r.mid - at.mid;
    const double n = d.norm();
    if (n < 0.5 || n > 6.0 || std::abs(wrap_angle(r.heading - at.heading)) > deg2rad(60)) continue;
    auto& slot = d.dot(h) > 0 ? ahead : behind;
    if (!slot || n < (*slot - at.mid).norm()) slot = r.mid;
  }
  if (!ahead || !behind) return {at.heading, 0.0};
  const Vec2 t = *ahead - *behind, a = at.mid - *behind, b = *ahead - at.mid;
  const double den = a.norm() * b.norm() * t.norm();
  return {std::atan2(t.y(), t.x()), den > 1e-9 ? 2.0 * cross2(a, b) / den : 0.0};
}

std::vector<Cone> visible_cones(const Track& track, const Pose2& car) {
  std::vector<Cone> out;
  for (const auto& c : track.cones) {
    const Vec2 local = car.inverse_transform(c.position);
    if (local.x() < 0 || local.norm() > 15.0) continue;
    Cone cone;
    cone.position = Vec3(c.position.x(), c.position.y(), 0);
    cone.colour = c.colour;
    out.push_back(cone);
  }
  return out;
}

// Limits on the checked part of the path. Track half widths are 1.5–2.4 m; a path point nearer than 0.5 m to a
// cone's centre is taken as outside the track.
struct Tolerance {
  double reach;            // m: path points within this distance of the car are checked
  double centre_max;       // m from the true centre line: a point farther is a bad placement
  double clearance_min;    // m from the nearest true cone: a point nearer is a bad placement
  double centre_rms;       // m, over every checked point of the track
  double failed_fraction;  // placements where the planner may report no plan (it must say so, not guess)
  double bad_fraction;     // placements whose checked path may be bad
};

struct Stats {
  int placements = 0, failed = 0, bad = 0;
  double worst_centre = 0, worst_clearance = 1e9, sum_sq = 0;
  long samples = 0;
};

Stats run_track(const std::string& name, Variant variant, const Tolerance& tol) {
  const Track full = test::shared_track(name);
  const TrackTruth truth(full);
  const Track track = variant_of(full, variant);
  const RealtimePlanner planner({}, PathConfig{}, track.convention, SpeedLimits{});
  Stats st;
  for (const auto& rung : truth.rungs()) {
    if (!rung.nearest) continue;
    VehicleState state;
    const OnCentre c = on_centre(truth, rung);
    state.pose = {rung.mid.x(), rung.mid.y(), c.heading};
    state.vx = 0.0;
    const auto cones = visible_cones(track, state.pose);
    if (cones.size() < 4) continue;  // the end of an open layout: nothing to plan through
    ++st.placements;
    const PlanResult plan = planner.plan(cones, state);
    if (!plan.ok) {
      EXPECT_FALSE(plan.reason.empty());
      if (std::getenv("FSD_PLAN_DEBUG")) std::printf("    no plan at (%.3f, %.3f, %.4f): %s\n", state.pose.x, state.pose.y, state.pose.yaw, plan.reason.c_str());
      ++st.failed;
      continue;
    }
    bool bad = false;
    for (const auto& p : plan.path.points) {
      const Vec2 local = state.pose.inverse_transform(p.p);
      if (local.x() < 0 || local.norm() > tol.reach) continue;
      const double c = truth.centre_distance(p.p);
      const double k = truth.cone_clearance(p.p);
      st.worst_centre = std::max(st.worst_centre, c);
      st.worst_clearance = std::min(st.worst_clearance, k);
      st.sum_sq += c * c;
      ++st.samples;
      bad = bad || c > tol.centre_max || k < tol.clearance_min;
    }
    if (bad) ++st.bad;
    if (bad && std::getenv("FSD_PLAN_DEBUG"))
      std::printf("    bad plan at (%.3f, %.3f, %.4f)\n", state.pose.x, state.pose.y, state.pose.yaw);
  }
  const double rms = st.samples ? std::sqrt(st.sum_sq / static_cast<double>(st.samples)) : 0.0;
  std::printf("  %-28s placements %4d no plan %3d bad %2d  centre max %.2f rms %.3f  clearance min %.2f\n",
              name.c_str(), st.placements, st.failed, st.bad, st.worst_centre, rms, st.worst_clearance);
  EXPECT_GT(st.placements, 10) << name;
  EXPECT_LE(rms, tol.centre_rms) << name;
  EXPECT_LE(st.failed, std::lround(tol.failed_fraction * st.placements)) << name;
  EXPECT_LE(st.bad, std::lround(tol.bad_fraction * st.placements)) << name;
  return st;
}

// A degraded variant on every loop: each layout within loose bounds, the set of them within tight ones. Without
// colours or with cones missing the planner picks a wrong branch near the edge of what it sees at a few
// placements where the layout itself is ambiguous (amz_fssim_thin packs its stretches of track within 3–4 m of
// each other; the autocross has a pointed 180° hairpin and a chicane that widens to 6 m): any one layout may have
// up to a fifth of its placements bad, all of them together at most `bad_fraction`. The same rule for every
// layout, none named.
void run_loops(Variant variant, Tolerance set) {
  Tolerance each = set;
  each.bad_fraction = std::max(set.bad_fraction, 0.2);
  each.centre_rms = std::max(set.centre_rms, 0.45);
  each.failed_fraction = std::max(set.failed_fraction, 0.15);  // the hairpins' apexes, as with every cone
  Stats all;
  for (const auto& name : test::loop_tracks()) {
    const Stats st = run_track(name, variant, each);
    all.placements += st.placements;
    all.bad += st.bad;
    all.sum_sq += st.sum_sq;
    all.samples += st.samples;
  }
  const double rms = all.samples ? std::sqrt(all.sum_sq / static_cast<double>(all.samples)) : 0.0;
  std::printf("  all layouts: placements %d bad %d  centre rms %.3f\n", all.placements, all.bad, rms);
  EXPECT_LE(all.bad, std::lround(set.bad_fraction * all.placements));
  EXPECT_LE(rms, set.centre_rms);
}

TEST(RealtimePlanner, FollowsTheTrueCentreOnEverySharedTrack) {
  // The line is the optimizer's: on the centre, cutting turns within the room (up to 0.8 m from the centre of a 5 m
  // lane, 0.68 m of a 3 m one). Standing on the centre line at the apex of the rules' tightest hairpin the car has no
  // path within its lock (it would only be there off its own line, which runs 0.1 m inside): up to a tenth of the
  // placements may have no plan, and say why; a wrong branch at the edge of the 15 m seen, 2 % of them.
  for (const auto& name : test::loop_tracks()) run_track(name, Variant::AllCones, {15.0, 0.8, 0.6, 0.13, 0.1, 0.02});
}

TEST(RealtimePlanner, FifthOfConesMissing) { run_loops(Variant::FifthRemoved, {8.0, 0.7, 0.5, 0.3, 0.06, 0.03}); }

TEST(RealtimePlanner, ColourBlind) { run_loops(Variant::ColourBlind, {8.0, 0.7, 0.5, 0.3, 0.03, 0.03}); }

// A tenth of the colours swapped is the hardest variant: a wrong-coloured cone at the edge of what is seen can
// bend the path's far end towards it until more cones come into view, and where a wrong colour hides one
// boundary the path runs the nominal half width (1.75 m) inside the other (0.75 m off centre on the 5 m wide
// epfl_VSV_XL). The planner always plans (a second, colour-blind walk wins when its geometry is clearly
// better, or when a wrong colour folds the coloured walk back short of where it could drive); the near field
// stays within 1 m of the centre and clear of the cones at 95 % of all placements (any one layout: four in five).
TEST(RealtimePlanner, TenthOfColoursWrong) { run_loops(Variant::WrongColours, {8.0, 1.0, 0.5, 0.7, 0.03, 0.05}); }

TEST(RealtimePlanner, StraightCorridorGivesTheCentreLineAndACurvatureSpeed) {
  // Hand-made straight: left cones at y = +1.5, right at y = −1.5 every 3 m; the car on the centre at x = 0.
  std::vector<Cone> cones;
  for (int i = 0; i < 8; ++i) {
    Cone l, r;
    l.position = Vec3(1.0 + 3.0 * i, 1.5, 0);
    l.colour = ConeColour::Blue;
    r.position = Vec3(1.0 + 3.0 * i, -1.5, 0);
    r.colour = ConeColour::Yellow;
    cones.push_back(l);
    cones.push_back(r);
  }
  SpeedLimits limits;
  limits.v_max = 8.0;
  PlannerConfig config;
  const RealtimePlanner planner(config, PathConfig{}, ColourConvention{}, limits);
  VehicleState state;
  state.vx = 3.0;
  const PlanResult plan = planner.plan(cones, state);
  ASSERT_TRUE(plan.ok) << plan.reason;
  EXPECT_GE(plan.path.length(), 18.0);
  for (const auto& p : plan.path.points) {
    EXPECT_NEAR(p.p.y(), 0.0, 0.05);
    EXPECT_NEAR(p.yaw, 0.0, 0.02);
    EXPECT_LE(p.v, limits.v_max + 1e-9);
  }
  // Speed starts at the car's speed and ends at the configured end speed (stop within what is seen).
  EXPECT_NEAR(plan.path.points.front().v, 3.0, 1e-9);
  EXPECT_NEAR(plan.path.points.back().v, config.end_speed, 1e-9);
}

TEST(RealtimePlanner, AWrongColourBesideAHairpinDoesNotTurnTheCarOffTheLane) {
  // epfl_autoX_Vaudoise_Sponso 1.3 m past its timing line, the car heading into the chicane before the pointed
  // hairpin at the top; one blue cone 6.6 m to the left taken for yellow (what the map held in a fused run). The
  // walk goes round the hairpin and ends beside the car: a long walk, to be driven, not replaced by one
  // boundary's offset (which swung the car 1.2 m right there and into the chicane's cones).
  Track track = test::shared_track("epfl_autoX_Vaudoise_Sponso");
  std::vector<Cone> cones;
  for (const auto& c : track.cones) {
    Cone k;
    k.position = Vec3(c.position.x(), c.position.y(), 0);
    k.colour = (c.position - Vec2(-4.5, 12.8038)).norm() < 0.01 ? ConeColour::Yellow : c.colour;
    cones.push_back(k);
  }
  const TrackTruth truth(track);
  const RealtimePlanner planner({}, PathConfig{}, track.convention, SpeedLimits{});
  VehicleState state;
  state.pose = {0.40, 8.63, 1.29};
  state.vx = 5.8;
  const PlanResult plan = planner.plan(cones, state);
  ASSERT_TRUE(plan.ok) << plan.reason;
  EXPECT_FALSE(plan.single_boundary);
  double worst = 0;
  for (const auto& p : plan.path.points) {
    if ((p.p - state.pose.position()).norm() > 8.0) break;
    worst = std::max(worst, truth.centre_distance(p.p));
  }
  EXPECT_LT(worst, 0.4);  // m from the centre over the first 8 m
}

TEST(RealtimePlanner, BadInputIsReportedNotThrown) {
  const RealtimePlanner planner({}, PathConfig{}, ColourConvention{}, SpeedLimits{});
  VehicleState state;
  EXPECT_FALSE(planner.plan({}, state).ok);
  std::vector<Cone> junk(3);
  junk[0].position = Vec3(std::nan(""), 0, 0);
  junk[1].position = Vec3(2, 1, 0);
  junk[2].position = Vec3(2, 1, 0);
  const PlanResult r = planner.plan(junk, state);
  EXPECT_FALSE(r.ok);
  EXPECT_FALSE(r.reason.empty());
  state.pose.x = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(planner.plan(junk, state).ok);
}

}  // namespace
}  // namespace fsd
