// run.localization_source = lidar_odometry on the virtual car: the car drives on the pose of its LiDAR odometry
// alone (the virtual VLP-16's packets through the real decoder, LOAM-style registration, integrated from the staging
// pose). The scorecard's "odometry" section holds the odometry's poses against the simulator's true ones, and its
// CTE is the car's true path against the true centre line, so a pose that is off shows as cross-track error, a
// cone hit or a drift figure. Also fused with the odometry's increments (localization.fusion.lidar_odometry).
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "tests/daemon/fsd_process.hpp"
#include "tests/daemon/sim_report.hpp"
#include "tests/scratch_dir.hpp"

namespace fsd {
namespace {

using nlohmann::json;

json drive(const std::string& name, const json& config, const std::string& track, int laps, bool must_pass = true) {
  return test::sim_report(name, config,
                          "--laps " + std::to_string(laps) + " --track ../shared/tracks/" + track + ".csv", must_pass);
}

// Two laps asked of a trackdrive the odometry was not tuned on (its lap figures are from epfl_track_1, _3 and
// fsds_competition_1 at a constant 8 m/s; here the car stands 10 s at the start, accelerates and brakes). The LiDAR
// alone does not yet drive a clean lap (docs/localization.md: its heading lags turn-in by up to 2 degrees, and the
// map placed by that heading skews): what is asserted is the source's own accuracy, not the run's verdict.
TEST(LidarOdometrySource, TheLidarOdometryAloneDriftsUnderOnePercentOfTheDistance) {
  const json r = drive("lidar_odometry_source",
                       {{"sim", {{"enable_camera", false}}},
                        {"run", {{"localization_source", "lidar_odometry"}, {"max_sim_time", 90.0}}}},
                       "epfl_track_2", 1, /*must_pass=*/false);
  ASSERT_TRUE(r.is_object());
  const json& o = r["odometry"];
  EXPECT_EQ(o["source"], "lidar_odometry");
  ASSERT_TRUE(o.contains("lidar")) << o.dump();
  EXPECT_GT(o["lidar"]["distance_m"].get<double>(), 250.0) << o.dump();  // a lap and more (337 m) is driven
  // The issue's bar: drift <= 1 % of the distance. Measured 0.13 % end-point, 1.13 % over 50 m stretches.
  EXPECT_LT(o["drift_pct"].get<double>(), 1.0) << o.dump();
  EXPECT_LT(o["lidar"]["segment_drift_pct"].get<double>(), 1.5) << o.dump();
  EXPECT_LT(o["ate_m"].get<double>(), 1.0) << o.dump();
  EXPECT_GT(r["latency_ms"]["odometry"]["n"].get<int>(), 300);
}

// The paper's fusion: GNSS-INS and the LiDAR odometry's increments (and the wheels) through the EKF.
TEST(LidarOdometrySource, FusedWithTheLidarOdometryDrivesTwoCleanLaps) {
  const json r = drive("fused_lidar_odometry",
                       {{"sim", {{"enable_camera", false}}},
                        {"run", {{"localization_source", "fused"}}},
                        {"localization", {{"fusion", {{"lidar_odometry", true}}}}}},
                       "epfl_track_1", 2);
  ASSERT_TRUE(r.is_object());
  EXPECT_EQ(r["verdict"], "pass") << r["verdict_reasons"].dump();
  EXPECT_EQ(r["cones_hit"], 0);
  const json& o = r["odometry"];
  EXPECT_EQ(o["source"], "fused");
  ASSERT_TRUE(o.contains("lidar")) << o.dump();
  EXPECT_LT(o["drift_pct"].get<double>(), 1.0) << o.dump();  // measured 0.61 % over 618 m
  // The issue's bar for the fused pose; measured 0.027 m.
  EXPECT_LT(o["ate_m"].get<double>(), 0.10) << o.dump();
}

TEST(LidarOdometrySource, WithoutTheVirtualLidarTheRunIsRefusedAtOnce) {
  const std::string cfg = test::scratch_path("lidar_odometry_no_lidar.json");
  std::ofstream(cfg) << R"({"sim": {"enable_lidar": false, "enable_camera": false},
                           "run": {"perception_source": "truth", "localization_source": "lidar_odometry"}})";
  std::string log;
  EXPECT_EQ(
      test::run_fsd("run --sim --headless --until-finished --track ../shared/tracks/epfl_track_1.csv --config " + cfg,
                    &log),
      2);
  EXPECT_NE(log.find("sim.enable_lidar"), std::string::npos) << log;
}

}  // namespace
}  // namespace fsd
