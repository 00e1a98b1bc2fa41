// Path following in closed loop with the test's own bicycle (tests/control/bicycle_sim.hpp): 60 ms command
// delay, steering lag and rate limit. The reference is the centre line of epfl_track_1 built here from the
// file's ordered boundaries; the cross-track error is measured by brute-force distance to that polyline.
#include <gtest/gtest.h>

#include <cstdio>
#include <numbers>

#include "control/tracking/follower.hpp"
#include "control/planning/smoothing.hpp"
#include "control/planning/speed_profile.hpp"
#include "tests/control/bicycle_sim.hpp"
#include "tests/control/path_helpers.hpp"
#include "tests/control/track_truth.hpp"

namespace fsd {
namespace {

// Centre line of a loop whose boundary cones are listed in driving order: each left cone's midpoint with the
// nearest right cone, in the left cones' order.
std::vector<Vec2> ordered_centre(const Track& track) {
  std::vector<Vec2> left, right, centre;
  for (const auto& c : track.cones) {
    if (c.role == ConeRole::Left) left.push_back(c.position);
    if (c.role == ConeRole::Right) right.push_back(c.position);
  }
  for (const auto& l : left) {
    const Vec2* best = &right.front();
    for (const auto& r : right)
      if ((r - l).norm() < (*best - l).norm()) best = &r;
    centre.push_back(0.5 * (l + *best));
  }
  return centre;
}

double polyline_distance(const std::vector<Vec2>& poly, const Vec2& p) {
  double best = 1e9;
  for (std::size_t i = 0; i < poly.size(); ++i)
    best = std::min(best, test::point_segment_distance(p, poly[i], poly[(i + 1) % poly.size()]));
  return best;
}

struct LoopResult {
  double max_cte = 0, rms_cte = 0, distance = 0;
};

LoopResult drive(FollowerConfig fc, const Path& path, const std::vector<Vec2>& reference, test::BicycleSim car,
                 double seconds, double control_period = 0.02) {
  PathFollower follower(fc);
  LoopResult r;
  double sum = 0;
  long n = 0;
  Vec2 last = car.pose.position();
  for (double t = 0; t < seconds; t += control_period) {
    const FollowResult f = follower.follow(path, car.state(), car.t, 30.0);
    EXPECT_TRUE(f.ok) << "t = " << t;
    if (!f.ok) break;
    car.command(f.command);
    car.run(control_period);
    const double cte = polyline_distance(reference, car.pose.position());
    r.max_cte = std::max(r.max_cte, cte);
    sum += cte * cte;
    ++n;
    r.distance += (car.pose.position() - last).norm();
    last = car.pose.position();
  }
  r.rms_cte = n ? std::sqrt(sum / static_cast<double>(n)) : 0;
  return r;
}

class FollowerOnTrack1 : public ::testing::TestWithParam<std::string> {};

TEST_P(FollowerOnTrack1, TracksTheCentreLineAtModerateSpeed) {
  const Track track = test::shared_track("epfl_track_1");
  const std::vector<Vec2> centre = ordered_centre(track);
  Path raw;
  raw.closed = true;
  for (const auto& c : centre) raw.points.push_back({c, 0, 0, 0, 0});
  Path path = smooth_path(raw, 0.25, 4.0);
  SpeedLimits limits;
  limits.mu = 0.6;
  limits.v_max = 10.0;
  SpeedProfile(limits).apply(path, 0, 0);

  test::BicycleSim car;
  car.pose = track.start;
  car.v = 3.0;
  FollowerConfig fc;
  fc.type = GetParam();
  fc.latency = car.delay + car.steer_tau;  // the follower knows the car's delay
  fc.lqr_sideslip_gain = 0;                // a kinematic bicycle: no tyre slip
  const LoopResult r = drive(fc, path, centre, car, 70.0);
  std::printf("  %-12s distance %.0f m  cte max %.3f m  rms %.3f m\n", GetParam().c_str(), r.distance, r.max_cte,
              r.rms_cte);
  EXPECT_GT(r.distance, path.length());  // more than a lap
  EXPECT_LT(r.max_cte, 0.35);
  EXPECT_LT(r.rms_cte, 0.12);
}

INSTANTIATE_TEST_SUITE_P(AllLaws, FollowerOnTrack1, ::testing::Values("pure_pursuit", "stanley", "lqr"));

TEST(Follower, PurePursuitConvergesOntoAStraightFromAnOffset) {
  Path line;
  for (int i = 0; i <= 200; ++i) line.points.push_back({Vec2(0.5 * i, 0.0), 0, 0, 0, 6.0});
  compute_geometry(line);
  test::BicycleSim car;
  car.pose = {0, 1.0, 0};
  car.v = 6.0;
  FollowerConfig pp;
  pp.type = "pure_pursuit";
  PathFollower follower(pp);
  double overshoot = 0, final_offset = 1.0;
  for (int k = 0; k < 400 && car.pose.x < 70; ++k) {
    const auto f = follower.follow(line, car.state(), car.t, 10.0);
    ASSERT_TRUE(f.ok);
    car.command(f.command);
    car.run(0.02);
    overshoot = std::max(overshoot, -car.pose.y);
    final_offset = std::abs(car.pose.y);
  }
  EXPECT_LT(final_offset, 0.02);
  EXPECT_LT(overshoot, 0.1);
}

TEST(Follower, LatencyPredictionIsTheBicycleArc) {
  // A quarter circle of radius R = L/tan δ at v: after t = (π/2)·R/v the car has turned 90°.
  const double L = 1.5, delta = 0.3, v = 4.0;
  const double R = L / std::tan(delta);
  const Pose2 p = predict_bicycle({0, 0, 0}, v, delta, L, 0.5 * std::numbers::pi * R / v);
  EXPECT_NEAR(p.x, R, 1e-9);
  EXPECT_NEAR(p.y, R, 1e-9);
  EXPECT_NEAR(p.yaw, std::numbers::pi / 2, 1e-9);
}

TEST(Follower, AnOlderStateIsCarriedToNowBeforeTheLawSteers) {
  // A straight along x; the car, steering δ = 0.2 rad at 10 m/s, turns off it on an arc of radius R = L/tan δ.
  // A state 20 ms old is the car that far back on that arc: carried to now it is the car as it stands now (the
  // arc, worked out by hand), so it gets the same command; the old pose taken as the car's now gets another.
  Path line;
  for (int i = 0; i <= 400; ++i) line.points.push_back({Vec2(0.25 * i - 20.0, 0.0), 0, 0, 0, 10.0});
  compute_geometry(line);
  const double v = 10.0, delta = 0.2, age = 0.02, now = 5.0;
  for (const char* law : {"pure_pursuit", "stanley", "lqr"}) {
    FollowerConfig fc;
    fc.type = law;
    fc.latency = 0.06;
    const double R = fc.wheelbase / std::tan(delta), th = v * age / R;
    VehicleState old, current;
    old.vx = current.vx = v;
    old.steering = current.steering = delta;
    old.stamp = now - age;
    old.pose = {0.0, 0.0, 0.0};
    current.stamp = now;
    current.pose = {R * std::sin(th), R * (1 - std::cos(th)), th};
    const double from_current = PathFollower(fc).follow(line, current, now, 30.0).command.steering;
    const double from_old = PathFollower(fc).follow(line, old, now, 30.0).command.steering;
    EXPECT_NEAR(from_old, from_current, 1e-6) << law;
    old.stamp = now;  // the old pose taken as the car's now
    const double stale = PathFollower(fc).follow(line, old, now, 30.0).command.steering;
    EXPECT_GT(std::abs(stale - from_current), 5e-3) << law;
  }
}

TEST(Follower, NoPathOrFarOffMeansStraightWheelsAndStop) {
  PathFollower follower;
  VehicleState s;
  s.vx = 5;
  auto f = follower.follow(Path{}, s, 1.0, 10.0);
  EXPECT_FALSE(f.ok);
  EXPECT_EQ(f.command.target_speed, 0.0);
  EXPECT_EQ(f.command.steering, 0.0);
  Path line;
  for (int i = 0; i <= 20; ++i) line.points.push_back({Vec2(i, 10.0), 0, 0, 0, 5.0});
  compute_geometry(line);
  f = follower.follow(line, s, 1.0, 10.0);
  EXPECT_FALSE(f.ok);
  EXPECT_EQ(f.command.target_speed, 0.0);
}

TEST(Follower, TargetSpeedIsCappedAndTakenAhead) {
  Path line;
  for (int i = 0; i <= 100; ++i) line.points.push_back({Vec2(i, 0.0), 0, 0, 0, i < 10 ? 8.0 : 3.0});
  compute_geometry(line);
  FollowerConfig fc;
  fc.latency = 0;
  fc.speed_preview = 0.5;
  PathFollower follower(fc);
  VehicleState s;
  s.vx = 8.0;
  s.pose = {5.0, 0, 0};
  // 0.5 s ahead at 8 m/s is x = 9: still 8 m/s... (between points 9 and 10 speeds blend)
  EXPECT_NEAR(follower.follow(line, s, 0, 20.0).command.target_speed, 8.0, 1e-9);
  s.pose.x = 7.0;  // preview reaches x = 11 where the path slows to 3
  EXPECT_NEAR(follower.follow(line, s, 0, 20.0).command.target_speed, 3.0, 1e-9);
  EXPECT_NEAR(follower.follow(line, s, 0, 2.0).command.target_speed, 2.0, 1e-9);
}

TEST(Follower, LqrHoldsTheCarPointingIntoTheCornerByTheRearSlip) {
  // On a circle of radius 20 m at 10 m/s (a_y = 5 m/s²) with gain 0.008 rad per m/s², a car on the line that
  // points 0.04 rad into the corner is where it should be: the LQR steers the pure feed-forward atan(L/R).
  Path circle = test::circle_path({0, 0}, 20.0, 2000);
  for (auto& q : circle.points) q.v = 10.0;
  FollowerConfig fc;
  fc.type = "lqr";
  fc.latency = 0;
  fc.lqr_preview = 0;
  fc.lqr_sideslip_gain = 0.008;
  VehicleState s;
  s.vx = 10.0;
  const double slip = 0.008 * 10.0 * 10.0 / 20.0;     // 0.04 rad
  s.pose = {20.0, 0.0, std::numbers::pi / 2 + slip};  // on the circle at angle 0, heading along it (+y) plus slip
  const double ff = std::atan(fc.wheelbase / 20.0);
  EXPECT_NEAR(PathFollower(fc).follow(circle, s, 0, 30.0).command.steering, ff, 2e-3);
  // Without the feed-forward the same pose is a heading error the LQR steers out of the corner against.
  fc.lqr_sideslip_gain = 0;
  EXPECT_LT(PathFollower(fc).follow(circle, s, 0, 30.0).command.steering, ff - 0.01);
}

TEST(Follower, OffTheLineOrOutOfSteeringTheCarDoesNotSpeedUp) {
  // A straight at 15 m/s; the car drives 10 m/s parallel to it.
  Path line;
  for (int i = 0; i <= 100; ++i) line.points.push_back({Vec2(i, 0.0), 0, 0, 0, 15.0});
  compute_geometry(line);
  FollowerConfig fc;
  fc.latency = 0;
  fc.governor_offset = 0.5;
  fc.governor_gain = 3.0;
  PathFollower follower(fc);
  VehicleState s;
  s.vx = 10.0;
  s.pose = {20.0, 0.3, 0};  // inside the offset: the path's speed
  EXPECT_NEAR(follower.follow(line, s, 0, 30.0).command.target_speed, 15.0, 1e-9);
  s.pose = {20.0, 1.5, 0};  // 1 m beyond it: 10 - 3·1 = 7 m/s
  auto f = follower.follow(line, s, 0, 30.0);
  EXPECT_NEAR(f.command.target_speed, 7.0, 1e-6);
  s.pose = {20.0, -1.0, 0};  // the other side, 0.5 m beyond: 8.5 m/s
  EXPECT_NEAR(follower.follow(line, s, 0, 30.0).command.target_speed, 8.5, 1e-6);
  // Heading 1 rad off the line at 0.4 m: the steering saturates, so no more than the car's speed.
  s.pose = {20.0, 0.4, 1.0};
  f = follower.follow(line, s, 0, 30.0);
  EXPECT_NEAR(std::abs(f.command.steering), fc.max_steer, 1e-12);
  EXPECT_NEAR(f.command.target_speed, 10.0, 1e-6);
  // Standing 1 m off the line, the car may still crawl back at the floor speed (2 m/s), not be held at rest.
  s.vx = 0.0;
  s.pose = {20.0, 1.5, 0};
  EXPECT_NEAR(follower.follow(line, s, 0, 30.0).command.target_speed, fc.governor_floor, 1e-9);
  EXPECT_GT(fc.governor_floor, 0.0);
  s.vx = 10.0;
  // Off: the path's speed whatever the offset.
  fc.governor_gain = 0;
  PathFollower plain(fc);
  s.pose = {20.0, 1.5, 0};
  EXPECT_NEAR(plain.follow(line, s, 0, 30.0).command.target_speed, 15.0, 1e-9);
}

}  // namespace
}  // namespace fsd
