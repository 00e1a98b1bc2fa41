// Whole missions in closed loop (tests/control/mission_harness.hpp): the Autopilot drives the test's bicycle
// car from AS Off to Finished. Ground truth is the track file: cross-track error to the true centre line
// (track_truth.hpp), cones inside the car's footprint, where the car stops.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "control/planning/smoothing.hpp"
#include "tests/control/mission_harness.hpp"
#include "tests/daemon/layouts/friction_limited_lap.hpp"

namespace fsd {
namespace {

const auto test_config = test::bicycle_autopilot_config;

void print_laps(const char* what, const test::MissionHarness& h) {
  std::printf("  %s:", what);
  for (const auto& l : h.laps()) std::printf(" lap %d %.2f s", l.lap, l.time_s);
  std::printf("  end (%.1f, %.1f) t %.1f s\n", h.car().pose.x, h.car().pose.y, h.car().t);
}

TEST(Autopilot, TrackdriveTwoLapsThenStopAndFinish) {
  const Track track = test::shared_track("epfl_track_1");
  test::HarnessOptions options;
  std::vector<std::pair<double, LapLineBuilt>> lap_lines;
  options.observe = [&](double t, const ControlOutput& out, const test::BicycleSim&) {
    if (out.lap_line) lap_lines.emplace_back(t, *out.lap_line);
  };
  test::MissionHarness h(track, Mission::Trackdrive, test_config(), options);
  h.run();
  print_laps("trackdrive epfl_track_1", h);
  ASSERT_EQ(h.laps().size(), 2u);
  EXPECT_EQ(h.as_state(), AsState::Finished);
  EXPECT_EQ(h.cones_hit(), 0);
  EXPECT_LT(h.moved_outside_driving(), 0.05);
  // Lap 2 on the recorded trajectory: at least 20 % faster, on the centre line.
  EXPECT_LT(h.laps()[1].time_s, 0.8 * h.laps()[0].time_s);
  const auto [rms2, max2] = h.lap_cte(2);
  const auto [rms1, max1] = h.lap_cte(1);
  std::printf("  cte lap 1 rms %.3f max %.3f, lap 2 rms %.3f max %.3f\n", rms1, max1, rms2, max2);
  EXPECT_LT(rms2, 0.15);
  EXPECT_LT(max2, 0.5);
  // Stopped within the stop distance after the line (epfl_track_1's line at y = 6, driving +y).
  const double past = h.car().pose.y - 6.0;
  EXPECT_GT(past, 0.0);
  EXPECT_LT(past, test_config().mission.stop_distance + 1.0);
  // Lap 2 against the friction-limited flying lap of the true centre line at the car's full μ (the speed
  // profile is checked against hand-computed values in speed_profile_test.cpp); the centre line is the file's
  // ordered left cones joined to their nearest right cones, smoothed like the lap-2 line. Lap 2 uses 92 % of
  // μ (≈ 4 % slower in corners) and starts at the lap-1 speed on the start straight, so it is allowed 10 %.
  Path centre;
  centre.closed = true;
  for (const auto& l : track.cones) {
    if (l.role != ConeRole::Left) continue;
    const TrackCone* best = nullptr;
    for (const auto& r : track.cones)
      if (r.role == ConeRole::Right &&
          (!best || (r.position - l.position).norm() < (best->position - l.position).norm()))
        best = &r;
    centre.points.push_back({0.5 * (l.position + best->position), 0, 0, 0, 0});
  }
  centre = smooth_path(centre, 0.25, 12.0);
  SpeedLimits full = test_config().speed.known();
  full.mu = test_config().speed.mu;
  SpeedProfile(full).apply(centre, 0, 0);
  const double t_ref = travel_time(centre);
  std::printf("  lap 2 %.2f s, friction-limited centre line %.2f s (+%.1f %%)\n", h.laps()[1].time_s, t_ref,
              100 * (h.laps()[1].time_s / t_ref - 1));
  EXPECT_LT(h.laps()[1].time_s, 1.10 * t_ref);
  // This bicycle has no tyres to limit it and its lap-2 line may cut the centre line's corners a little (the
  // optimizer's curvature cost against its centre cost): it can beat the centre line's friction limit, not by much.
  EXPECT_GT(h.laps()[1].time_s, 0.95 * t_ref);
  // The lap path was built once, shortly before the end of lap 1, as long as the lap and closed.
  ASSERT_EQ(lap_lines.size(), 1u);
  EXPECT_LT(lap_lines[0].first, h.laps()[0].t);
  EXPECT_GT(lap_lines[0].first, h.laps()[0].t - 5.0);
  EXPECT_NEAR(lap_lines[0].second.length, centre.length(), 0.03 * centre.length());
  EXPECT_LT(lap_lines[0].second.closure_gap, 1.0);
  EXPECT_GT(lap_lines[0].second.recentre_rms, 0.0);
  // The lap's line keeps the body clear of every mapped cone (the optimizer's margin, less its tolerance).
  EXPECT_GT(lap_lines[0].second.clearance, test_config().path.accept_clearance);
  bool used_recorded = false;
  for (const auto& r : h.records()) used_recorded = used_recorded || r.source == PathSource::Recorded;
  EXPECT_TRUE(used_recorded);
  // The lap-2 profile runs at control.lap2.mu_margin of mu: v²|κ| reaches that share of µg in the corners and
  // never exceeds it.
  const AutopilotConfig cfg = test_config();
  const double a_lat_max = cfg.lap2.mu_margin * cfg.speed.mu * 9.81;
  double a_lat_peak = 0;
  ASSERT_NE(h.autopilot().recorded_path(), nullptr);
  for (const auto& q : h.autopilot().recorded_path()->points)
    a_lat_peak = std::max(a_lat_peak, q.v * q.v * std::abs(q.kappa));
  EXPECT_LE(a_lat_peak, a_lat_max * 1.001);
  EXPECT_GE(a_lat_peak, a_lat_max * 0.95);
  EXPECT_TRUE(h.autopilot().faults().empty());
}

}  // namespace
}  // namespace fsd

namespace fsd {
namespace {

class TrackdriveOnEveryLoop : public ::testing::TestWithParam<std::string> {};

TEST_P(TrackdriveOnEveryLoop, TwoLapsNoConesHitFinished) {
  const Track track = test::shared_track(GetParam());
  test::MissionHarness h(track, Mission::Trackdrive, test_config());
  h.run();
  print_laps(GetParam().c_str(), h);
  EXPECT_EQ(h.laps().size(), 2u);
  EXPECT_EQ(h.as_state(), AsState::Finished);
  for (const auto& [t, c] : h.hits()) std::printf("    hit cone (%.2f, %.2f) at t %.2f\n", c.x(), c.y(), t);
  EXPECT_EQ(h.cones_hit(), 0);
  // Lap 2 at least 20 % faster than lap 1, or, where the layout allows less, within 5 % of the gain the two laps'
  // speed limits give on its true centre line (friction_limited_lap.hpp, from the file alone: lap 1 at
  // mu_margin_realtime and v_max_realtime, lap 2 at lap2.mu_margin and v_max). The layouts here allow 32–46 %,
  // but epfl_autoX_Vaudoise_Sponso, all corners, 22 % (the car gains 19 %).
  const auto& sp = test_config().speed;
  const auto file_cones = test::read_cones("../shared/tracks/" + GetParam() + ".csv");
  const double layout_ratio =
      test::friction_limited_lap_time(
          file_cones, {sp.mu * test_config().lap2.mu_margin, sp.a_accel_max, sp.a_brake_max, sp.v_max}) /
      test::friction_limited_lap_time(
          file_cones, {sp.mu * sp.mu_margin_realtime, sp.a_accel_max, sp.a_brake_max, sp.v_max_realtime});
  const double ratio_max = std::max(0.8, layout_ratio + 0.05);
  std::printf("    lap 2 / lap 1 allowed %.3f (centre line at the two laps' limits %.3f)\n", ratio_max, layout_ratio);
  // The lap-2 figures: 20 % faster than lap 1, CTE RMS < 0.15 m, max < 0.5 m. Two centre lines are
  // drawn from the file independently of control: this harness's (rungs between facing cones) and the
  // scorecard's yardstick (sim::ReferenceLine, DESIGN.md §8: each left-boundary point's midpoint with its
  // closest right-boundary point). They agree within centimetres except where a boundary turns sharply at one
  // cone across a wide stretch (amz_fssim_thin's (29.5, 11.6): 1 m apart); the error is to the nearer of the two.
  const sim::ReferenceLine reference(track);
  if (h.laps().size() == 2) {
    EXPECT_LT(h.laps()[1].time_s, ratio_max * h.laps()[0].time_s);
    const auto [rms2, max2] = h.lap_cte(2, &reference);
    std::printf("    lap 2 cte rms %.3f max %.3f\n", rms2, max2);
    EXPECT_LT(rms2, 0.15);
    EXPECT_LT(max2, 0.5);
  }
  for (const auto& f : h.autopilot().faults()) ADD_FAILURE() << f.t << " " << f.source << ": " << f.what;
}

INSTANTIATE_TEST_SUITE_P(SharedLoops, TrackdriveOnEveryLoop,
                         ::testing::Values("epfl_track_2", "epfl_track_3", "epfl_track_4", "epfl_track_5",
                                           "epfl_fsds_competition_1", "epfl_fsds_competition_2",
                                           "epfl_fsds_competition_3", "epfl_fsds_default", "epfl_autoX_Vaudoise_Sponso",
                                           "epfl_21_05_2023", "amz_fssim_thin"));

}  // namespace
}  // namespace fsd

namespace fsd {
namespace {

TEST(Autopilot, AutocrossOneLap) {
  const Track track = test::shared_track("epfl_fsds_competition_1");
  test::MissionHarness h(track, Mission::Autocross, test_config());
  h.run();
  print_laps("autocross", h);
  ASSERT_EQ(h.laps().size(), 1u);
  EXPECT_EQ(h.as_state(), AsState::Finished);
  EXPECT_EQ(h.cones_hit(), 0);
  for (const auto& r : h.records()) EXPECT_NE(r.source, PathSource::Recorded);
}

TEST(Autopilot, AccelerationStopsInTheBrakingZone) {
  for (const char* name : {"epfl_acceleration", "amz_fssim_acceleration"}) {
    SCOPED_TRACE(name);
    const Track track = test::shared_track(name);
    AutopilotConfig c = test_config();
    test::MissionHarness h(track, Mission::Acceleration, c);
    h.run();
    print_laps(name, h);
    ASSERT_EQ(h.laps().size(), 1u);
    EXPECT_EQ(h.as_state(), AsState::Finished);
    EXPECT_EQ(h.cones_hit(), 0);
    // Finish line 75 m past the start line; the braking zone is the 100 m after it (to the last cones).
    const auto start = timing_line_from_cones(
        [&] {
          std::vector<Cone> v;
          for (const auto& k : track.cones) v.push_back({Vec3(k.position.x(), k.position.y(), 0), k.colour});
          return v;
        }(),
        track.start, track.convention);
    ASSERT_TRUE(start);
    const double past_start = start->past(h.car().pose.position());
    EXPECT_GT(past_start, 75.0);
    EXPECT_LT(past_start, 75.0 + c.mission.acceleration_stop_distance);
    // Lower bound: full traction (a_max) from standstill at the start pose, capped at v_max, timed from the
    // start line to 75 m past it. The car never drives faster than stops it, braking (a_brake_max) after the
    // latency, a margin short of where the sensor range ends less its nose: v_sight = −a·t + √((a·t)² + 2·a·d).
    // A good run is within a second of that speed's time (the speed loop lags).
    const double ab = c.speed.a_brake_max, lat = c.speed.stop_latency;
    const double d_sight = test::HarnessOptions{}.sensor_range - 2.4 - c.speed.stop_margin;
    const double v_sight = -ab * lat + std::sqrt(ab * ab * lat * lat + 2 * ab * d_sight);
    const double a = c.speed.a_accel_max;
    const double d0 = -start->past(track.start.position());
    auto run_time = [&](double vm) {
      const double sc = vm * vm / (2 * a);
      auto time_to = [&](double s) { return s <= sc ? std::sqrt(2 * s / a) : vm / a + (s - sc) / vm; };
      return time_to(d0 + 75.0) - time_to(d0);
    };
    const double t_min = run_time(c.speed.v_max), t_sight = run_time(std::min(c.speed.v_max, v_sight));
    std::printf("    run %.2f s, bound %.2f s, at the sight's speed %.2f s\n", h.laps()[0].time_s, t_min, t_sight);
    EXPECT_GT(h.laps()[0].time_s, t_min);
    EXPECT_LT(h.laps()[0].time_s, t_sight + 1.0);
    double vmax = 0;
    for (const auto& r : h.records()) vmax = std::max(vmax, r.speed);
    EXPECT_LE(vmax, std::min(c.speed.v_max, v_sight) + 0.3);
  }
}

TEST(Autopilot, SkidpadRightTwiceLeftTwiceThenStop) {
  const Track track = test::shared_track("epfl_skidpad");
  AutopilotConfig c = test_config();
  test::MissionHarness h(track, Mission::Skidpad, c);
  h.run();
  print_laps("skidpad", h);
  ASSERT_EQ(h.laps().size(), 4u);
  EXPECT_EQ(h.as_state(), AsState::Finished);
  EXPECT_EQ(h.cones_hit(), 0);
  // Steady laps (2nd and 4th, the timed ones in the rules) at √(μ·margin·g·R) on R = 9.125 m.
  const double v = std::sqrt(c.speed.mu * c.speed.mu_margin_known * 9.81 * 9.125);
  const double t_lap = 2 * std::numbers::pi * 9.125 / v;
  EXPECT_NEAR(h.laps()[1].time_s, t_lap, 0.05 * t_lap);
  EXPECT_NEAR(h.laps()[3].time_s, t_lap, 0.05 * t_lap);
  // Right circle first: during lap 1 the car is on the right (x > 0) side; lap 3 on the left.
  const auto& L = h.laps();
  for (const auto& r : h.records()) {
    if (r.t > L[0].t - L[0].time_s + 1 && r.t < L[1].t - 1) {
      EXPECT_GT(r.position.x(), -0.5);
    }
    if (r.t > L[2].t - L[2].time_s + 1 && r.t < L[3].t - 1) {
      EXPECT_LT(r.position.x(), 0.5);
    }
  }
  // Exit straight ahead, stopped within the stop distance past the crossing (y = 15).
  EXPECT_NEAR(h.car().pose.x, 0.0, 0.3);
  EXPECT_GT(h.car().pose.y, 15.0);
  EXPECT_LT(h.car().pose.y, 15.0 + c.mission.stop_distance + 1.0);
}

TEST(Autopilot, InspectionSweepsTheSteeringThenFinishes) {
  const Track track = test::shared_track("epfl_acceleration");
  AutopilotConfig c = test_config();
  double min_cmd = 0, max_cmd = 0;
  test::HarnessOptions o;
  o.observe = [&](double, const ControlOutput& out, const test::BicycleSim&) {
    min_cmd = std::min(min_cmd, out.command.steering);
    max_cmd = std::max(max_cmd, out.command.steering);
  };
  test::MissionHarness h(track, Mission::Inspection, c, o);
  h.run();
  EXPECT_EQ(h.as_state(), AsState::Finished);
  EXPECT_NEAR(max_cmd, c.mission.inspection_amplitude * c.follower.max_steer, 0.01);
  EXPECT_NEAR(min_cmd, -c.mission.inspection_amplitude * c.follower.max_steer, 0.01);
  ASSERT_TRUE(h.finished_at());
  EXPECT_GT(*h.finished_at(), 5.0 + c.mission.inspection_duration);  // Driving began after the 5 s go delay
}

TEST(Autopilot, EbsTestAsksForEmergencyAtSpeed) {
  const Track track = test::shared_track("epfl_ebs_test_fss");
  AutopilotConfig c = test_config();
  test::MissionHarness h(track, Mission::EbsTest, c);
  h.run();
  EXPECT_EQ(h.as_state(), AsState::Emergency);
  ASSERT_TRUE(h.emergency_at());
  double v_at = 0;
  for (const auto& r : h.records())
    if (std::abs(r.t - *h.emergency_at()) < 0.011) v_at = r.speed;
  EXPECT_GT(v_at, 10.0);
  EXPECT_EQ(h.cones_hit(), 0);
}

TEST(Autopilot, GnssLostOnLapTwoFallsBackToRealtimePlanning) {
  const Track track = test::shared_track("epfl_track_1");
  test::HarnessOptions o;
  // Lap 1 ends near t = 43 s (5 s go delay + 38 s); GNSS is bad from 50 s to 60 s of lap 2.
  o.gnss_good = [](double t) { return t < 50.0 || t > 60.0; };
  test::MissionHarness h(track, Mission::Trackdrive, test_config(), o);
  h.run();
  print_laps("gnss loss", h);
  ASSERT_EQ(h.laps().size(), 2u);
  EXPECT_EQ(h.as_state(), AsState::Finished);
  EXPECT_EQ(h.cones_hit(), 0);
  bool planner_in_gap = false, recorded_after = false;
  for (const auto& r : h.records()) {
    if (r.t > 50.1 && r.t < 59.9) {
      EXPECT_EQ(r.source, PathSource::Planner) << r.t;
      planner_in_gap = true;
    }
    if (r.t > 60.2 && r.laps_done == 1) recorded_after = recorded_after || r.source == PathSource::Recorded;
  }
  EXPECT_TRUE(planner_in_gap);
  EXPECT_TRUE(recorded_after);
  ASSERT_FALSE(h.autopilot().faults().empty());
  const Fault& f = h.autopilot().faults().front();
  EXPECT_EQ(f.source, "gnss");
  EXPECT_EQ(f.action, "fallback to real-time planning");
  EXPECT_NEAR(f.t, 50.0, 0.03);  // the first bad fix (a silent GNSS would count after gnss_timeout)
}

TEST(Autopilot, LidarLostForOneSecondSlowsAndRecovers) {
  const Track track = test::shared_track("epfl_track_1");
  test::HarnessOptions o;
  o.lidar_alive = [](double t) { return t < 20.0 || t > 21.0; };  // lap 1, on the planner
  test::MissionHarness h(track, Mission::Trackdrive, test_config(), o);
  h.run();
  ASSERT_EQ(h.laps().size(), 2u);
  EXPECT_EQ(h.as_state(), AsState::Finished);
  EXPECT_EQ(h.cones_hit(), 0);
  for (const auto& r : h.records())
    if (r.t > 20.6 && r.t < 21.0) {
      EXPECT_LT(r.speed, test_config().supervisor.degraded_speed + 2.5) << r.t;
    }
  ASSERT_EQ(h.autopilot().faults().size(), 1u);
  EXPECT_EQ(h.autopilot().faults()[0].source, "lidar");
}

TEST(Autopilot, PlannerStallIsAControlledStop) {
  const Track track = test::shared_track("epfl_track_1");
  test::HarnessOptions o;
  o.planner_stalled = [](double t) { return t > 15.0; };
  test::MissionHarness h(track, Mission::Trackdrive, test_config(), o);
  h.run();
  EXPECT_EQ(h.as_state(), AsState::Emergency);  // stopped, then the EBS holds it
  EXPECT_EQ(h.cones_hit(), 0);
  ASSERT_FALSE(h.autopilot().faults().empty());
  const Fault& f = h.autopilot().faults().front();
  EXPECT_EQ(f.source, "planning");
  EXPECT_EQ(f.action, "controlled stop");
  EXPECT_NEAR(f.t, 15.0 + test_config().supervisor.plan_timeout, 0.15);
  ASSERT_TRUE(h.emergency_at());
  // Braked to standstill before asking for the EBS.
  for (const auto& r : h.records())
    if (std::abs(r.t - *h.emergency_at()) < 0.011) {
      EXPECT_LT(r.speed, 0.1);
    }
}

}  // namespace
}  // namespace fsd

namespace fsd {
namespace {

class EverySharedLayout : public ::testing::TestWithParam<std::pair<std::string, Mission>> {};

TEST_P(EverySharedLayout, FinishesWithoutHittingCones) {
  const auto& [name, mission] = GetParam();
  const Track track = test::shared_track(name);
  test::MissionHarness h(track, mission, test_config());
  h.run();
  print_laps(name.c_str(), h);
  EXPECT_EQ(h.as_state(), AsState::Finished);
  EXPECT_EQ(h.cones_hit(), 0);
  EXPECT_EQ(h.laps().size(), mission == Mission::Skidpad ? 4u : 1u);
  for (const auto& f : h.autopilot().faults()) ADD_FAILURE() << f.t << " " << f.source << ": " << f.what;
}

INSTANTIATE_TEST_SUITE_P(AccelerationAndSkidpad, EverySharedLayout,
                         ::testing::Values(std::make_pair("epfl_acceleration_4m", Mission::Acceleration),
                                           std::make_pair("epfl_acceleration_4_5m", Mission::Acceleration),
                                           std::make_pair("epfl_acceleration_5_5m", Mission::Acceleration),
                                           std::make_pair("epfl_acceleration_large", Mission::Acceleration),
                                           std::make_pair("epfl_skidpad_v2", Mission::Skidpad),
                                           std::make_pair("epfl_skidpad_reversed", Mission::Skidpad),
                                           std::make_pair("epfl_skidpad_minimalist", Mission::Skidpad),
                                           std::make_pair("epfl_short_skidpad", Mission::Skidpad),
                                           std::make_pair("amz_fssim_skidpad", Mission::Skidpad)));

}  // namespace
}  // namespace fsd
