// TrackdriveMission alone (trackdrive, autocross, open layouts): the car is moved by hand round a circle of
// radius 20 m centred at (0, 20) at 10 m/s (0.5 rad/s), through a timing line of big orange cones at (0, ±2), so
// that each lap takes 4π s and the line is crossed where the circle passes x = 0 at its bottom; and along a
// straight lane that ends.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "control/missions/mission_trackdrive.hpp"
#include "tests/control/mission_world.hpp"
#include "tests/control/path_helpers.hpp"

namespace fsd {
namespace {

using test::cone_at;

constexpr double kR = 20.0, kV = 10.0, kOmega = kV / kR;
constexpr double kPhi0 = -0.25;  // rad round the circle at the start: 5 m before the line
constexpr double kDt = 0.02;

AutopilotConfig circle_config() {
  AutopilotConfig c;
  c.trajectory.early_build_distance = 0;  // lap 2's path built at the line
  c.trajectory.recentre = false;          // from the driven circle alone (no boundary cones here)
  return c;
}

// Drives the circle: every kDt the car moves on, the mission updates its path and progresses.
struct CircleDrive {
  TrackdriveMission& run;
  test::MissionWorld world;
  std::vector<LapEvent> laps;
  std::vector<std::pair<Stamp, LapLineBuilt>> lap_lines;
  std::vector<std::pair<Stamp, MissionPath>> paths;
  std::vector<MissionFault> faults;
  double odometer_at_lap = 0;  // when the newest lap ended
  int step = 0;

  explicit CircleDrive(TrackdriveMission& r) : run(r) {
    place(0.0);
    world.see(0.0, {cone_at(0, 2, ConeColour::BigOrange), cone_at(0, -2, ConeColour::BigOrange)});
    world.plan = test::circle_path({0.0, kR}, kR, 400);  // stands in for the real-time plan
    run.start(world.input(0.0));
  }
  void place(Stamp t) {
    const double phi = kPhi0 + kOmega * t;
    world.move(t, {kR * std::sin(phi), kR - kR * std::cos(phi)}, phi, kV);
  }
  // Until time t_end.
  void drive(Stamp t_end) {
    while ((step + 1) * kDt <= t_end + 1e-9) {
      const Stamp t = ++step * kDt;
      place(t);
      const MissionInput in = world.input(t);
      MissionPath p = run.update_path(in);
      for (const auto& f : p.faults) faults.push_back(f);
      paths.emplace_back(t, std::move(p));
      const MissionEvents e = run.progress(in, nullptr);
      for (const auto& l : e.laps) laps.push_back(l);
      if (!e.laps.empty()) odometer_at_lap = world.odometer;
      if (e.lap_line) lap_lines.emplace_back(t, *e.lap_line);
      for (const auto& f : e.faults) faults.push_back(f);
    }
  }
};

// The line is crossed 0.5 s after the start (0.25 rad at 0.5 rad/s), then every 4π s.
constexpr double kFirstCrossing = 0.5, kLap = 4 * std::numbers::pi;

TEST(TrackdriveMission, AutocrossIsOneLapOnThePlanThenAStop) {
  AutopilotConfig config = circle_config();
  config.mission.stop_distance = 10.0;  // short enough to set the braking below (stop_decel alone takes 12.5 m)
  TrackdriveMission run(config, Mission::Autocross, ColourConvention{});
  EXPECT_TRUE(run.uses_planner());
  EXPECT_EQ(run.target_laps(), 1);
  CircleDrive d(run);
  d.drive(kFirstCrossing + kLap - 0.1);
  EXPECT_TRUE(d.laps.empty());
  EXPECT_FALSE(run.finished());
  d.drive(kFirstCrossing + kLap + 0.1);
  ASSERT_EQ(d.laps.size(), 1u);
  EXPECT_EQ(d.laps[0].lap, 1);
  EXPECT_NEAR(d.laps[0].t, kFirstCrossing + kLap, 1e-3);
  EXPECT_NEAR(d.laps[0].time_s, kLap, 1e-3);
  EXPECT_TRUE(run.finished());
  EXPECT_TRUE(d.lap_lines.empty());  // autocross records no lap
  for (const auto& [t, p] : d.paths) {
    ASSERT_EQ(p.source, PathSource::Planner) << t;
    ASSERT_EQ(p.path, &*d.world.plan) << t;
    ASSERT_FALSE(p.fixed) << t;  // the planner's heartbeat is its own
  }
  EXPECT_TRUE(d.faults.empty());

  // The stop after the finish, from 10 m/s: stop_decel (4 m/s²) would take 12.5 m, more than 80 % of the 10 m
  // allowed, so it brakes at 10² / (1.6 · 10) = 6.25 m/s² and stops in 8 m: √(2 · 6.25 · (8 − travelled)).
  d.drive(kFirstCrossing + kLap + 0.6);
  const double travelled = d.world.odometer - d.odometer_at_lap;
  ASSERT_GT(travelled, 4.0);
  ASSERT_LT(travelled, 8.0);
  ControlCommand cmd;
  cmd.target_speed = 20.0;
  run.limit(d.world.input(d.step * kDt), cmd);
  EXPECT_NEAR(cmd.target_speed, std::sqrt(2 * 6.25 * (8.0 - travelled)), 1e-9);
}

TEST(TrackdriveMission, NotFinishedNoStop) {
  TrackdriveMission run(circle_config(), Mission::Autocross, ColourConvention{});
  CircleDrive d(run);
  d.drive(1.0);
  ControlCommand cmd;
  cmd.target_speed = 20.0;
  run.limit(d.world.input(1.0), cmd);
  EXPECT_EQ(cmd.target_speed, 20.0);
}

TEST(TrackdriveMission, TrackdriveFollowsTheRecordedLapFromLapTwoWhileGnssIsGood) {
  AutopilotConfig config = circle_config();
  config.mission.laps = 2;
  TrackdriveMission run(config, Mission::Trackdrive, ColourConvention{});
  CircleDrive d(run);
  d.drive(kFirstCrossing + kLap + 0.1);
  ASSERT_EQ(d.laps.size(), 1u);
  EXPECT_NEAR(d.laps[0].time_s, kLap, 1e-3);
  EXPECT_FALSE(run.finished());
  // Built at the line from lap 1's poses: a closed lap as long as the circle.
  ASSERT_EQ(d.lap_lines.size(), 1u);
  EXPECT_NEAR(d.lap_lines[0].first, d.laps[0].t, kDt);
  ASSERT_NE(run.lap_path(), nullptr);
  EXPECT_TRUE(run.lap_path()->closed);
  EXPECT_NEAR(d.lap_lines[0].second.length, 2 * std::numbers::pi * kR, 0.02 * 2 * std::numbers::pi * kR);
  EXPECT_LT(d.lap_lines[0].second.closure_gap, 0.5);
  // Its speed is lap 2's share of μ (control.lap2.mu_margin) round the circle: v² / R = μ · 0.97 · g.
  const double v_lap2 = std::sqrt(config.speed.mu * config.lap2.mu_margin * 9.81 * kR);
  const PathPoint& half_way = run.lap_path()->points[run.lap_path()->points.size() / 2];
  EXPECT_NEAR(half_way.v, v_lap2, 0.02 * v_lap2);
  // Before the line the plan, after it the recorded lap, with the GNSS fault cleared each cycle.
  for (const auto& [t, p] : d.paths) {
    if (t <= d.lap_lines[0].first) {
      ASSERT_EQ(p.source, PathSource::Planner) << t;
    } else {
      ASSERT_EQ(p.source, PathSource::Recorded) << t;
      ASSERT_EQ(p.path, run.lap_path()) << t;
    }
  }
  ASSERT_FALSE(d.faults.empty());
  for (const auto& f : d.faults) {
    EXPECT_TRUE(f.source == "gnss" || f.source == "localization") << f.source;
    EXPECT_FALSE(f.active);
  }

  // A live change of μ re-profiles the stored lap.
  AutopilotConfig slower = config;
  slower.speed.mu = 1.0;
  run.set_config(slower);
  EXPECT_NEAR(half_way.v, std::sqrt(1.0 * config.lap2.mu_margin * 9.81 * kR), 0.02 * v_lap2);

  // GNSS lost while the pose matches the cone map: the recorded lap is kept, with a fault that says so.
  d.faults.clear();
  d.world.gnss_ok = false;
  d.world.map_matched = true;
  d.paths.clear();
  d.drive(kFirstCrossing + kLap + 0.5);
  for (const auto& [t, p] : d.paths) ASSERT_EQ(p.source, PathSource::Recorded) << t;
  ASSERT_FALSE(d.faults.empty());
  for (const auto& f : d.faults) {
    if (f.what == "fix lost, the pose held to the cone map") {
      EXPECT_EQ(f.action, "recorded lap kept");
      EXPECT_TRUE(f.active);
    } else {
      EXPECT_FALSE(f.active) << f.source << ": " << f.what;  // a fix was had: neither the plain loss nor the map's
    }
  }

  // GNSS lost and no match either: back on the plan, and a fault for as long as it lasts.
  d.faults.clear();
  d.world.map_matched = false;
  d.paths.clear();
  d.drive(kFirstCrossing + kLap + 1.0);
  for (const auto& [t, p] : d.paths) ASSERT_EQ(p.source, PathSource::Planner) << t;
  ASSERT_FALSE(d.faults.empty());
  EXPECT_EQ(d.faults.front().source, "gnss");
  EXPECT_EQ(d.faults.front().what, "fix lost");
  EXPECT_EQ(d.faults.front().action, "fallback to real-time planning");
  EXPECT_TRUE(d.faults.front().active);

  d.world.gnss_ok = true;
  d.drive(kFirstCrossing + 2 * kLap + 0.1);
  ASSERT_EQ(d.laps.size(), 2u);
  EXPECT_EQ(d.laps[1].lap, 2);
  EXPECT_NEAR(d.laps[1].time_s, kLap, 1e-3);
  EXPECT_TRUE(run.finished());
}

TEST(TrackdriveMission, WithoutSatellitesTheConeMapAloneAnchorsLapTwo) {
  // No good fix ever (run.localization_source = lidar_odometry): lap 2 keeps the recorded lap while the pose
  // matches the cone map, with no GNSS fault; without a match it falls back to the plan, the fault naming the map.
  AutopilotConfig config = circle_config();
  config.mission.laps = 2;
  TrackdriveMission run(config, Mission::Trackdrive, ColourConvention{});
  CircleDrive d(run);
  d.world.gnss_ok = d.world.gnss_seen = false;
  d.world.map_matched = true;
  d.drive(kFirstCrossing + kLap + 0.5);
  ASSERT_EQ(d.laps.size(), 1u);
  ASSERT_NE(run.lap_path(), nullptr);
  for (const auto& [t, p] : d.paths) {
    if (t > d.laps[0].t + 0.1) {
      ASSERT_EQ(p.source, PathSource::Recorded) << t;
    }
  }
  for (const auto& f : d.faults) EXPECT_FALSE(f.active) << f.source << ": " << f.what;

  d.faults.clear();
  d.paths.clear();
  d.world.map_matched = false;
  d.drive(kFirstCrossing + kLap + 1.0);
  for (const auto& [t, p] : d.paths) ASSERT_EQ(p.source, PathSource::Planner) << t;
  bool named = false;
  for (const auto& f : d.faults) {
    if (!f.active) continue;
    EXPECT_EQ(f.source, "localization");
    EXPECT_EQ(f.what, "pose not matched to the cone map");
    EXPECT_EQ(f.action, "fallback to real-time planning");
    named = true;
  }
  EXPECT_TRUE(named);
}

TEST(TrackdriveMission, ALoopClosureMovesTheRecordedLapAndTheLapPathIsBuiltAgainFromIt) {
  AutopilotConfig config = circle_config();
  config.mission.laps = 2;
  TrackdriveMission run(config, Mission::Trackdrive, ColourConvention{});
  CircleDrive d(run);
  d.drive(kFirstCrossing + kLap + 0.1);
  ASSERT_EQ(d.lap_lines.size(), 1u);
  ASSERT_NE(run.lap_path(), nullptr);
  auto centroid = [](const Path& p) {
    Vec2 c = Vec2::Zero();
    for (const auto& q : p.points) c += q.p;
    return Vec2(c / double(p.points.size()));
  };
  const Vec2 before = centroid(*run.lap_path());
  // A correction of nothing (a later lap's closure, before which lap 1's poses lie) keeps the path as built.
  run.relocate([](Stamp) { return Pose2{}; }, d.step * kDt);
  ASSERT_NE(run.lap_path(), nullptr);
  // Lap 1's poses 0.5 m off along x: the lap path goes, the recorded lap follows the plan meanwhile, and the next
  // cycle builds it again from the moved poses.
  run.relocate([](Stamp) { return Pose2{-0.5, 0, 0}; }, d.step * kDt);
  EXPECT_EQ(run.lap_path(), nullptr);
  d.paths.clear();
  d.drive(kFirstCrossing + kLap + 0.2);
  ASSERT_EQ(d.lap_lines.size(), 2u);
  ASSERT_NE(run.lap_path(), nullptr);
  const Vec2 after = centroid(*run.lap_path());
  EXPECT_NEAR(after.x() - before.x(), -0.5, 0.02);
  EXPECT_NEAR(after.y() - before.y(), 0.0, 0.02);
  EXPECT_EQ(d.paths.back().second.source, PathSource::Recorded);
}

TEST(TrackdriveMission, AStartJustPastTheLineTimesLapOneFromTheStart) {
  // Big orange cones 3 m behind the start: the first lap runs from the start to the first crossing.
  AutopilotConfig config = circle_config();
  TrackdriveMission run(config, Mission::Autocross, ColourConvention{});
  test::MissionWorld world;
  world.move(2.0, {0.0, 0.0}, 0, 0);
  world.see(2.0, {cone_at(-3, 2, ConeColour::BigOrange), cone_at(-3, -2, ConeColour::BigOrange)});
  run.start(world.input(2.0));
  ASSERT_NE(run.lap_counter(), nullptr);
  EXPECT_TRUE(run.lap_counter()->timing());
  EXPECT_NEAR(run.lap_counter()->line().mid().x(), -3.0, 1e-9);
}

// An open layout: a lane 3 m wide from x = 0 to x = 40 (cones every 5 m), the start line's big orange cones at
// x = 2. The car drives +x at 10 m/s from the origin, 1 m per 0.1 s cycle; the real-time plan runs from the car
// to x = 40.5, where its walk between the cones stops.
struct OpenLane : ::testing::Test {
  AutopilotConfig config;
  test::MissionWorld world;
  double lane_end = 40;
  bool cones_after_2s = true;  // false: the cone maps stop coming at t = 2 s
  bool finish_line = false;    // true: a finish line's four big orange cones at finish_x + 0.6 and + 1.8
  double finish_x = 40;
  double plan_end = 40.5;  // where the real-time plan's walk between the cones stops

  std::vector<Cone> lane() const {
    std::vector<Cone> c{cone_at(2, 2, ConeColour::BigOrange), cone_at(2, -2, ConeColour::BigOrange)};
    if (finish_line)
      for (const double x : {finish_x + 0.6, finish_x + 1.8})
        for (const double y : {2.0, -2.0}) c.push_back(cone_at(x, y, ConeColour::BigOrange));
    for (int x = 0; x <= lane_end; x += 5) {
      c.push_back(cone_at(x, 1.5, ConeColour::Blue));
      c.push_back(cone_at(x, -1.5, ConeColour::Yellow));
    }
    return c;
  }
  void start(TrackdriveMission& run) {
    world.move(0.0, {0.0, 0.0}, 0, kV);
    world.see(0.0, lane());
    run.start(world.input(0.0));
  }
  // Cycles k = from..to (x = k m, t = 0.1 k s); the path of the last one.
  MissionPath drive(TrackdriveMission& run, int from, int to) {
    MissionPath p;
    for (int k = from; k <= to; ++k) {
      const Stamp t = 0.1 * k;
      world.move(t, {1.0 * k, 0.0}, 0, kV);
      if (cones_after_2s || t <= 2.0) world.see(t, lane());
      world.plan = test::straight_path({1.0 * k, 0.0}, 0, plan_end - k, 0.25);
      world.plan_ok = true;
      p = run.update_path(world.input(t));
      run.progress(world.input(t), nullptr);
    }
    return p;
  }
};

TEST_F(OpenLane, WhereThePlanEndsWithNoConeBeyondTheRunEndsAndTheCarStopsStraightOn) {
  TrackdriveMission run(config, Mission::Trackdrive, ColourConvention{});
  start(run);
  // 12.5 m from the plan's end: not yet within open_end_sight (12 m).
  EXPECT_EQ(drive(run, 1, 28).source, PathSource::Planner);
  EXPECT_FALSE(run.open_end_seen());
  // In sight from x = 29 (11.5 m), believed once it stayed so over open_end_confirm (3 m) driven: at x = 32.
  ASSERT_EQ(config.mission.open_end_confirm, 3.0);
  EXPECT_EQ(drive(run, 29, 31).source, PathSource::Planner);
  EXPECT_FALSE(run.open_end_seen());
  const MissionPath p = drive(run, 32, 32);
  ASSERT_NE(p.path, nullptr);
  EXPECT_EQ(p.source, PathSource::Straight);
  EXPECT_TRUE(p.fixed);
  EXPECT_TRUE(p.replaced);
  EXPECT_TRUE(run.open_end_seen());
  // The plan (x 32 → 40.5), then straight on for the stop distance (25 m), down to standstill.
  EXPECT_NEAR(p.path->points.front().p.x(), 32.0, 1e-9);
  EXPECT_NEAR(p.path->points.back().p.x(), 40.5 + config.mission.stop_distance, config.planner.ds);
  for (const auto& q : p.path->points) ASSERT_NEAR(q.p.y(), 0.0, 1e-9);
  EXPECT_NEAR(p.path->points.back().v, 0.0, 1e-9);

  // One run, timed from the start line (crossed at x = 2, t = 0.2 s) to the plan's end (8.5 m on the path).
  for (int k = 33; k <= 41; ++k) {
    const Stamp t = 0.1 * k;
    world.move(t, {1.0 * k, 0.0}, 0, kV);
    world.plan_ok = false;
    EXPECT_EQ(run.update_path(world.input(t)).source, PathSource::Straight);
    const FollowResult f = test::followed_at(k - 32.0);
    const MissionEvents e = run.progress(world.input(t), &f);
    if (k < 41) {
      EXPECT_TRUE(e.laps.empty()) << k;
    } else {
      ASSERT_EQ(e.laps.size(), 1u);
      EXPECT_EQ(e.laps[0].lap, 1);
      EXPECT_NEAR(e.laps[0].time_s, 4.1 - 0.2, 1e-9);
    }
  }
  EXPECT_TRUE(run.finished());
}

// The generated open courses end at a finish line: its big orange cones stand beyond the walk's end (x = 40.5), and
// are no track going on.
TEST_F(OpenLane, AFinishLineAtTheEndIsNoTrackGoingOn) {
  finish_line = true;
  TrackdriveMission run(config, Mission::Trackdrive, ColourConvention{});
  start(run);
  EXPECT_EQ(drive(run, 1, 31).source, PathSource::Planner);
  EXPECT_FALSE(run.open_end_seen());
  EXPECT_EQ(drive(run, 32, 32).source, PathSource::Straight);
  EXPECT_TRUE(run.open_end_seen());
}

// An open course whose finish line lies beside another part of it (the cones go on, and the plan with them): the run
// ends at the line, x = 41.2, and the car stops straight on.
TEST_F(OpenLane, AFinishLineEndsTheRunWhereTheConesGoOn) {
  finish_line = true;
  lane_end = 60;
  plan_end = 60.5;
  TrackdriveMission run(config, Mission::Trackdrive, ColourConvention{});
  start(run);
  // Its cones within open_end_sight (12 m) from x = 29, believed over open_end_confirm (3 m) driven: at x = 32.
  EXPECT_EQ(drive(run, 1, 31).source, PathSource::Planner);
  const MissionPath p = drive(run, 32, 32);
  ASSERT_NE(p.path, nullptr);
  EXPECT_EQ(p.source, PathSource::Straight);
  EXPECT_NEAR(p.path->points.back().p.x(), 41.2 + config.mission.stop_distance, config.planner.ds);
  EXPECT_NEAR(p.path->points.back().v, 0.0, 1e-9);
  // One run, timed from the start line (x = 2, t = 0.2 s) to the finish line (9.2 m on the path).
  for (int k = 33; k <= 42; ++k) {
    const Stamp t = 0.1 * k;
    world.move(t, {1.0 * k, 0.0}, 0, kV);
    const FollowResult f = test::followed_at(k - 32.0);
    const MissionEvents e = run.progress(world.input(t), &f);
    EXPECT_EQ(e.laps.size(), k == 42 ? 1u : 0u) << k;
  }
  EXPECT_TRUE(run.finished());
}

// A loop's start line, met again at the end of lap 1, is no finish line of an open course.
TEST_F(OpenLane, TheStartLineIsNoFinishLine) {
  TrackdriveMission run(config, Mission::Trackdrive, ColourConvention{});
  start(run);
  lane_end = 60;
  plan_end = 60.5;
  EXPECT_EQ(drive(run, 1, 8).source, PathSource::Planner);
  // Back behind the start line (as at the end of a lap), it is ahead in sight.
  for (int k = 9; k <= 20; ++k) {
    const Stamp t = 0.1 * k;
    world.move(t, {-9.0 + 0.5 * (k - 9), 0.0}, 0, kV);
    world.see(t, lane());
    world.plan = test::straight_path({-9.0 + 0.5 * (k - 9), 0.0}, 0, 20, 0.25);
    world.plan_ok = true;
    EXPECT_EQ(run.update_path(world.input(t)).source, PathSource::Planner) << k;
  }
  EXPECT_FALSE(run.open_end_seen());
}

TEST_F(OpenLane, APlanThatEndsShortForAMomentIsNoEnd) {
  // The lane goes on to x = 60, but until x = 30 only its cones up to x = 40 are mapped (a turn beyond the walk's
  // end that the perception has not confirmed yet) and the plan ends at x = 40.5: in sight for 2 m, then the cones
  // beyond come in and the plan runs on.
  TrackdriveMission run(config, Mission::Trackdrive, ColourConvention{});
  start(run);
  EXPECT_EQ(drive(run, 1, 30).source, PathSource::Planner);
  lane_end = 60;
  plan_end = 60.5;
  EXPECT_EQ(drive(run, 31, 45).source, PathSource::Planner);  // a run-out, once taken, stays
  EXPECT_FALSE(run.open_end_seen());
}

TEST_F(OpenLane, ConesBeyondThePlanMeanTheTrackGoesOn) {
  lane_end = 60;
  TrackdriveMission run(config, Mission::Trackdrive, ColourConvention{});
  start(run);
  const MissionPath p = drive(run, 1, 35);
  EXPECT_EQ(p.source, PathSource::Planner);
  EXPECT_FALSE(p.fixed);
  EXPECT_FALSE(run.open_end_seen());
}

TEST_F(OpenLane, NoEndIsBelievedOnAStaleView) {
  cones_after_2s = false;
  TrackdriveMission run(config, Mission::Trackdrive, ColourConvention{});
  start(run);
  EXPECT_EQ(drive(run, 1, 35).source, PathSource::Planner);
  EXPECT_FALSE(run.open_end_seen());
}

}  // namespace
}  // namespace fsd
