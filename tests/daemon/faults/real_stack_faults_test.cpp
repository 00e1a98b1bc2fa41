// Faults on the real stack (the defaults: the LiDAR and camera stages, GNSS-INS fused with the wheels and the LiDAR
// odometry), as docs/faults.md says each ends. Each run is `fsd run --sim` on epfl_track_1, two laps, with one
// injected fault (sim.faults.*); the outcome and the cones hit come from the simulator's truth.
#include <gtest/gtest.h>

#include <string>

#include <nlohmann/json.hpp>

#include "tests/daemon/faults/fault_run.hpp"

namespace fsd {
namespace {

using nlohmann::json;
using test::faults_of;
using test::FsdRun;
using test::injected;
using test::run_with_faults;
using test::Sources;

void expect_clean_two_laps(const FsdRun& r) {
  ASSERT_EQ(r.rc, 0) << r.log;
  EXPECT_TRUE(r.report["finished"]);
  EXPECT_TRUE(r.report["stopped_after_finish"]);
  EXPECT_EQ(r.report["as_state"], "Finished");
  EXPECT_EQ(r.report["cones_hit"], 0);
  EXPECT_EQ(r.report["laps"].size(), 2u);
  EXPECT_EQ(r.report["perception"]["source"], "lidar_camera");
  EXPECT_EQ(r.report["odometry"]["source"], "fused");
}

TEST(RealStackFaults, CameraLostForGoodTheLidarStagesFinishBothLaps) {
  const FsdRun r = run_with_faults("real_camera_lost", {{"camera", {{"lap", 1}, {"at_s", 10.0}}}}, Sources::Real);
  expect_clean_two_laps(r);
  const json& inj = injected(r, "camera");
  const double start = inj["start_s"].get<double>();
  EXPECT_TRUE(inj["end_s"].is_null());
  // The stack notices 0.5 s after the last frame (20 Hz: the last one came at most 0.05 s before the window).
  const auto cam = faults_of(r, "camera");
  ASSERT_EQ(cam.size(), 1u) << r.report["faults"].dump();
  EXPECT_EQ(cam[0]["action"], "LiDAR-only detections, colour from reflectivity");
  EXPECT_GE(cam[0]["t"].get<double>(), start + 0.5 - 0.06);
  EXPECT_LE(cam[0]["t"].get<double>(), start + 0.5 + 0.02);
  EXPECT_FALSE(cam[0].contains("cleared_t"));  // never came back
  // Not a stop: no other fault.
  EXPECT_EQ(r.report["faults"].size(), 1u) << r.report["faults"].dump();
}

TEST(RealStackFaults, ACameraThatComesBackMidLapIsUsedAgain) {
  const FsdRun r = run_with_faults("real_camera_back", {{"camera", {{"lap", 1}, {"at_s", 10.0}, {"duration_s", 5.0}}}},
                                   Sources::Real);
  expect_clean_two_laps(r);
  const json& inj = injected(r, "camera");
  const double end = inj["end_s"].get<double>();
  const auto cam = faults_of(r, "camera");
  ASSERT_EQ(cam.size(), 1u) << r.report["faults"].dump();
  // Cleared with the first frame sent after the window (20 Hz), which the virtual car hands over at its capture,
  // up to the camera's latency before it is stamped as sent.
  ASSERT_TRUE(cam[0].contains("cleared_t")) << cam[0].dump();
  EXPECT_GE(cam[0]["cleared_t"].get<double>(), end - 0.1);
  EXPECT_LE(cam[0]["cleared_t"].get<double>(), end + 0.05 + 0.02);
  // Colour from the camera again: the map the car drove on is coloured as on a run without the fault.
  EXPECT_GE(r.report["map"]["colour_accuracy"].get<double>(), 0.98) << r.report["map"].dump();
}

TEST(RealStackFaults, LidarLostForOneSecondTheCarSlowsThenCarriesOn) {
  const FsdRun r =
      run_with_faults("real_lidar", {{"lidar", {{"lap", 1}, {"at_s", 10.0}, {"duration_s", 1.0}}}}, Sources::Real);
  expect_clean_two_laps(r);
  test::expect_slowed_and_recovered(r);
}

TEST(RealStackFaults, GnssFixLostForGoodOnLapTwoTheLapIsDrivenOnThePoseHeldToTheConeMap) {
  // The receiver loses its fix 3 s into lap 2 and never gets it back (no_fix: the INS's rates go on). The fused
  // pose is held to the lap-1 cone map, so lap 2 stays on the recorded lap (real-time planning on a drifting pose
  // put new cones beside the mapped ones and hit four).
  const FsdRun r = run_with_faults("real_gnss_lap2", {{"gnss", {{"lap", 2}, {"at_s", 3.0}}}}, Sources::Real);
  expect_clean_two_laps(r);
  const double start = injected(r, "gnss")["start_s"].get<double>();
  const auto gnss = faults_of(r, "gnss");
  ASSERT_EQ(gnss.size(), 1u) << r.report["faults"].dump();
  EXPECT_EQ(gnss[0]["what"], "fix lost, the pose held to the cone map");
  EXPECT_EQ(gnss[0]["action"], "recorded lap kept");
  EXPECT_GE(gnss[0]["t"].get<double>(), start);
  EXPECT_LE(gnss[0]["t"].get<double>(), start + 0.6);  // control.gnss_timeout after the last good fix
  EXPECT_EQ(r.report["faults"].size(), 1u) << r.report["faults"].dump();  // no fallback, no guard, no stop
  // Lap 2 on the recorded lap: as fast and as close to the centre line as with the fix (0.14 m RMS there).
  EXPECT_LE(r.report["laps"][1]["cte_rms_m"].get<double>(), 0.15);
  EXPECT_LE(r.report["laps"][1]["time_s"].get<double>(), 0.65 * r.report["laps"][0]["time_s"].get<double>());
}

TEST(RealStackFaults, GnssInsSilentOnLapTwoTheWheelsStandInForItsGyro) {
  // The whole GNSS-INS unit goes quiet 3 s into lap 2 and stays so: no fix, no heading, and no yaw rate, the car's
  // only gyro. The wheels' kinematic yaw rate (speed and measured steering) stands in for it in the fusion, the pose
  // is held to the lap-1 cone map, and lap 2 stays on the recorded lap (without the stand-in the scans' deskew lost
  // the car's turn and it hit 3 cones).
  const FsdRun r =
      run_with_faults("real_gnss_silent", {{"gnss", {{"lap", 2}, {"at_s", 3.0}, {"mode", "silent"}}}}, Sources::Real);
  expect_clean_two_laps(r);
  const auto gnss = faults_of(r, "gnss");
  ASSERT_EQ(gnss.size(), 1u) << r.report["faults"].dump();
  EXPECT_EQ(gnss[0]["what"], "fix lost, the pose held to the cone map");
  EXPECT_LE(r.report["laps"][1]["cte_rms_m"].get<double>(), 0.15);
}

}  // namespace
}  // namespace fsd
