// `fsd run --sim --vs-truth`: the scorecard's "vs_truth" is what the same layout and seed give on the truth sources.
// Checked against an independent run of the reference (a separate fsd with the truth sources: headless runs are the
// same bit for bit), and the side-by-side rows against hand-made scorecards.
#include <gtest/gtest.h>

#include <string>

#include <nlohmann/json.hpp>

#include "daemon/scoring/vs_truth.hpp"
#include "tests/daemon/fsd_process.hpp"
#include "tests/daemon/sim_report.hpp"
#include "tests/truth_sources.hpp"

namespace fsd {
namespace {

using nlohmann::json;

const std::string kTrack = "--mission acceleration --track ../shared/tracks/epfl_acceleration.csv --seed 2";

TEST(VsTruth, TheReferenceIsTheSameLayoutDrivenOnTheTruthSources) {
  // The defaults: the car's own perception and the fused pose.
  const json run = test::sim_report("vs_truth_real", json::object(), kTrack + " --vs-truth");
  ASSERT_TRUE(run.contains("vs_truth")) << run.dump(2);
  EXPECT_EQ(run["perception"]["source"], "lidar_camera");
  EXPECT_EQ(run["odometry"]["source"], "fused");
  // The reference on its own, as a user would run it.
  const json truth = test::sim_report("vs_truth_reference", test::truth_sources_json(), kTrack);
  const json& vs = run["vs_truth"];
  EXPECT_EQ(vs["source"], "truth");
  EXPECT_EQ(vs["finished"], truth["finished"]);
  EXPECT_EQ(vs["cones_hit"], truth["cones_hit"]);
  ASSERT_EQ(vs["laps"].size(), 1u) << vs.dump(2);
  ASSERT_EQ(truth["laps"].size(), 1u);
  const json& row = vs["laps"][0];
  EXPECT_EQ(row["truth_time_s"], truth["laps"][0]["time_s"]);
  EXPECT_EQ(row["truth_cte_rms_m"], truth["laps"][0]["cte_rms_m"]);
  EXPECT_EQ(row["time_s"], run["laps"][0]["time_s"]);
  EXPECT_EQ(row["cte_rms_m"], run["laps"][0]["cte_rms_m"]);
  const double t = run["laps"][0]["time_s"], tt = truth["laps"][0]["time_s"];
  EXPECT_NEAR(row["time_delta_pct"].get<double>(), 100.0 * (t / tt - 1.0), 1e-3);
}

TEST(VsTruth, WithoutTheSimulatorThereIsNoTruthToCompareWith) {
  std::string log;
  EXPECT_EQ(test::run_fsd("run --headless --vs-truth", &log), 2) << log;
  EXPECT_NE(log.find("--vs-truth"), std::string::npos) << log;
  EXPECT_NE(log.find("--sim"), std::string::npos) << log;
}

TEST(VsTruth, LapsOnlyOneRunDroveKeepTheirOneSide) {
  const json estimated = {{"laps", {{{"lap", 1}, {"time_s", 50.0}, {"cte_rms_m", 0.2}, {"cte_max_m", 0.5}}}}};
  const json truth = {{"finished", true},
                      {"cones_hit", 0},
                      {"verdict", "pass"},
                      {"laps",
                       {{{"lap", 1}, {"time_s", 40.0}, {"cte_rms_m", 0.1}, {"cte_max_m", 0.3}},
                        {{"lap", 2}, {"time_s", 30.0}, {"cte_rms_m", 0.05}, {"cte_max_m", 0.2}}}}};
  const json vs = vs_truth(estimated, truth);
  ASSERT_EQ(vs["laps"].size(), 2u);
  EXPECT_DOUBLE_EQ(vs["laps"][0]["time_delta_pct"].get<double>(), 25.0);  // 50 s against 40 s
  EXPECT_DOUBLE_EQ(vs["laps"][0]["truth_cte_max_m"].get<double>(), 0.3);
  EXPECT_FALSE(vs["laps"][1].contains("time_s"));
  EXPECT_FALSE(vs["laps"][1].contains("time_delta_pct"));
  EXPECT_DOUBLE_EQ(vs["laps"][1]["truth_time_s"].get<double>(), 30.0);
  EXPECT_EQ(vs["verdict"], "pass");
}

}  // namespace
}  // namespace fsd
