// Fault tests through the whole stack, as a user runs them: `fsd run --sim --headless --until-finished` with a
// fault schedule (sim.faults.*) on epfl_track_1, LiDAR and camera models off (truth perception; the LiDAR outage
// then starves the perception feed). Each test asserts on the scorecard: the mission outcome and cones hit from
// the truth, the stack's own fault log, and the truth trace the scorecard keeps around each injected fault
// ("injected_faults"), from which the reaction (braking, speed drop, stop) is measured here.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <fstream>
#include <string>
#include <utility>

#include <unistd.h>

#include <nlohmann/json.hpp>

#include "tests/daemon/faults/fault_run.hpp"

namespace fsd {
namespace {

using nlohmann::json;
using test::faults_of;
using test::FsdRun;
using test::injected;
using test::run_with_faults;
using test::expect_slowed_and_recovered;
using test::speed_at;

TEST(FaultInjection, WithoutFaultsTheRunHasNone) {
  const FsdRun r = run_with_faults("none", nullptr);
  ASSERT_EQ(r.rc, 0) << r.log;
  EXPECT_TRUE(r.report["faults"].empty()) << r.report["faults"].dump();
  EXPECT_TRUE(r.report["injected_faults"].empty());
}

TEST(FaultInjection, GnssLostOnLapTwoRealtimePlanningTakesOverAndTheLapCompletes) {
  // The fix lost from 3 s into lap 2 for 8 s: most of the lap is driven on real-time planning. no_fix: the stack
  // notices the first epoch without a fix (50 Hz, 10 ms latency); silent: control.gnss_timeout (0.5 s) after
  // the last good sample.
  for (const auto& [mode, delay] : {std::pair<std::string, double>{"no_fix", 0.0}, {"silent", 0.5}}) {
    SCOPED_TRACE(mode);
    const FsdRun r =
        run_with_faults("gnss_" + mode, {{"gnss", {{"lap", 2}, {"at_s", 3.0}, {"duration_s", 8.0}, {"mode", mode}}}});
    ASSERT_EQ(r.rc, 0) << r.log;
    const json& rep = r.report;
    EXPECT_TRUE(rep["finished"]);
    EXPECT_TRUE(rep["stopped_after_finish"]);
    EXPECT_EQ(rep["as_state"], "Finished");
    EXPECT_EQ(rep["cones_hit"], 0);
    ASSERT_EQ(rep["laps"].size(), 2u);
    const json& inj = injected(r, "gnss");
    const double start = inj["start_s"].get<double>();
    // Lap 2 begins after the 5 s in Ready and the whole of lap 1.
    EXPECT_GT(start, 5.0 + rep["laps"][0]["time_s"].get<double>() + 3.0);
    EXPECT_NEAR(inj["end_s"].get<double>() - start, 8.0, 1e-9);
    const auto gnss = faults_of(r, "gnss");
    ASSERT_EQ(gnss.size(), 1u) << rep["faults"].dump();
    EXPECT_EQ(gnss[0]["what"], "fix lost");
    EXPECT_EQ(gnss[0]["action"], "fallback to real-time planning");
    // Silent: 0.5 s after the last good epoch, stamped at its epoch time (the receiver's latency is accounted),
    // which may lie up to one epoch (20 ms at 50 Hz) before the window opens.
    EXPECT_GE(gnss[0]["t"].get<double>(), start + delay - (delay > 0 ? 0.02 : 0.0));
    EXPECT_LE(gnss[0]["t"].get<double>(), start + delay + 0.05);
    // Nothing else went wrong: no stop, no other fault.
    EXPECT_EQ(rep["faults"].size(), 1u) << rep["faults"].dump();
    // The car kept driving through the outage (never below walking pace).
    for (const auto& v : inj["trace"]["speed_m_s"]) EXPECT_GT(v.get<double>(), 2.0);
  }
}

TEST(FaultInjection, LidarLostForOneSecondTheCarSlowsAndRecovers) {
  // Without the VLP-16 model the outage starves the truth perception feed.
  const FsdRun r = run_with_faults("lidar", {{"lidar", {{"lap", 1}, {"at_s", 10.0}, {"duration_s", 1.0}}}});
  ASSERT_EQ(r.rc, 0) << r.log;
  EXPECT_TRUE(r.report["finished"]);
  EXPECT_EQ(r.report["as_state"], "Finished");
  ASSERT_EQ(r.report["laps"].size(), 2u);
  expect_slowed_and_recovered(r);
}

TEST(FaultInjection, SilentVlp16StarvesPerceptionThroughTheScanBuilder) {
  // With the VLP-16 simulated, perception runs on complete scans: the silent sensor itself starves it. Lap 1 only
  // (22 s of simulated time: the window is at ~17.4 s) to keep the slower run short.
  const FsdRun r =
      run_with_faults("lidar_on", {{"lidar", {{"lap", 1}, {"at_s", 10.0}, {"duration_s", 1.0}}}},
                      test::Sources::TruthWithLidar, 22.0);
  ASSERT_FALSE(r.report.is_null()) << r.log;
  expect_slowed_and_recovered(r);
}

TEST(FaultInjection, VcuLinkLostTheStandinBrakesWithin200ms) {
  const FsdRun r = run_with_faults("vcu", {{"vcu_link", {{"lap", 1}, {"at_s", 10.0}}}});
  EXPECT_EQ(r.rc, 1) << r.log;  // the mission failed
  const json& rep = r.report;
  EXPECT_EQ(rep["as_state"], "Emergency");
  EXPECT_FALSE(rep["finished"]);
  const json& inj = injected(r, "vcu_link");
  const double cut = inj["start_s"].get<double>();
  EXPECT_TRUE(inj["end_s"].is_null());
  // The VCU's own watchdog: no Command for 0.1 s → Emergency (EBS).
  ASSERT_FALSE(inj["as_transitions"].empty());
  const json& em = inj["as_transitions"][0];
  EXPECT_EQ(em["to"], "Emergency");
  EXPECT_NE(em["why"].get<std::string>().find("heartbeat lost"), std::string::npos) << em.dump();
  EXPECT_GE(em["t"].get<double>(), cut + 0.09);
  EXPECT_LE(em["t"].get<double>(), cut + 0.11);
  // From the truth: the car decelerates hard from at most 200 ms after the cut until it stands.
  const double v0 = inj["speed_at_start_m_s"].get<double>();
  EXPECT_GT(v0, 5.0);
  ASSERT_FALSE(inj["stopped_at_s"].is_null());
  const double stopped = inj["stopped_at_s"].get<double>();
  const auto& ts = inj["trace"]["t_s"];
  int braking = 0;
  for (std::size_t i = 0; i < ts.size(); ++i) {
    const double t = ts[i].get<double>();
    // (Below 0.2 m/s the vehicle model creeps to rest without a tyre force: ax reads 0 there.)
    if (t >= cut + 0.2 && inj["trace"]["speed_m_s"][i].get<double>() > 0.2) {
      EXPECT_LT(inj["trace"]["ax_m_s2"][i].get<double>(), -6.0) << t;
      ++braking;
    }
  }
  EXPECT_GT(braking, 10);
  EXPECT_LT(speed_at(inj, cut + 0.3), v0 - 1.0);
  // Braking at ≥ 6 m/s² from v0 after ≤ 0.2 s at v0 (the car cannot speed up much in 0.2 s).
  EXPECT_LE(stopped - cut, 0.2 + v0 / 6.0);
  EXPECT_LE(inj["stop_distance_m"].get<double>(), v0 * 0.2 + v0 * v0 / (2 * 6.0) + 0.5);
  // The daemon's side saw the link go quiet too: the scorecard names it.
  const auto vcu = faults_of(r, "vcu");
  ASSERT_FALSE(vcu.empty()) << rep["faults"].dump();
  EXPECT_GE(vcu[0]["t"].get<double>(), cut);
}

TEST(FaultInjection, PlannerStalledIsAControlledStop) {
  const FsdRun r = run_with_faults("stall", {{"planner_stall", {{"lap", 1}, {"at_s", 10.0}}}});
  EXPECT_EQ(r.rc, 1) << r.log;  // the mission was not completed
  const json& rep = r.report;
  EXPECT_EQ(rep["cones_hit"], 0);
  const json& inj = injected(r, "planner_stall");
  const double stall = inj["start_s"].get<double>();
  // The planning watchdog (control.supervisor.plan_timeout 0.5 s after the last plan) stops the car.
  const auto planning = faults_of(r, "planning");
  ASSERT_EQ(planning.size(), 1u) << rep["faults"].dump();
  EXPECT_EQ(planning[0]["action"], "controlled stop");
  // The log says why the car stops, once.
  const std::string line = "planning: no usable plan for 0.50 s -> controlled stop";
  EXPECT_NE(r.log.find(line), std::string::npos) << r.log;
  EXPECT_EQ(r.log.find(line), r.log.rfind(line)) << r.log;
  EXPECT_GE(planning[0]["t"].get<double>(), stall + 0.5 - 0.1);  // the last plan came at most 0.1 s earlier
  EXPECT_LE(planning[0]["t"].get<double>(), stall + 0.5 + 0.02);
  // From the truth: the service brakes stop the car; only then does the stack ask for the EBS to hold it
  // (control.supervisor.emergency_after_fault_stop), so AS Emergency is entered at standstill.
  const double v0 = inj["speed_at_start_m_s"].get<double>();
  EXPECT_GT(v0, 5.0);
  ASSERT_FALSE(inj["stopped_at_s"].is_null());
  const double stopped = inj["stopped_at_s"].get<double>();
  const double t_stop = planning[0]["t"].get<double>();
  // Hand bound: full service braking (≥ 6 m/s² on this car) from at most v0 + 1 after the watchdog's 0.5 s.
  EXPECT_LE(stopped - t_stop, (v0 + 1.0) / 6.0 + 0.2);
  EXPECT_LE(inj["stop_distance_m"].get<double>(), (v0 + 1.0) * 0.52 + (v0 + 1.0) * (v0 + 1.0) / (2 * 6.0));
  ASSERT_EQ(inj["as_transitions"].size(), 1u) << inj["as_transitions"].dump();
  const json& em = inj["as_transitions"][0];
  EXPECT_EQ(em["to"], "Emergency");
  EXPECT_EQ(em["why"], "the stack requested an emergency stop");
  EXPECT_GE(em["t"].get<double>(), stopped);
  EXPECT_LT(speed_at(inj, em["t"].get<double>()), 0.1);
  EXPECT_EQ(rep["as_state"], "Emergency");
}

}  // namespace
}  // namespace fsd
