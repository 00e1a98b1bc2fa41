// Runs that cannot succeed fail at once with exit status 2 and a message naming the problem; the scorecard's verdict
// says pass or fail with the reasons a run failed.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "tests/daemon/fsd_process.hpp"
#include "tests/scratch_dir.hpp"
#include "tests/truth_sources.hpp"

namespace fsd {
namespace {

const std::string kFast = test::truth_sources();

std::string write(const std::string& name, const std::string& text) {
  const auto p = test::scratch_path(name);
  std::ofstream(p) << text;
  return p;
}

TEST(RunRefusals, ASkidPadMissionOnALoopIsRefusedBeforeItDrives) {
  std::string out;
  const int rc = test::run_fsd(
      "run --sim --headless --until-finished --mission skidpad --track "
      "../shared/tracks/epfl_track_1.csv",
      &out);
  EXPECT_EQ(rc, 2) << out;
  EXPECT_NE(out.find("no skid pad"), std::string::npos) << out;
  EXPECT_EQ(out.find("lap 1 in"), std::string::npos) << out;  // nothing was driven
}

TEST(RunRefusals, AnAccelerationMissionWithoutALaneIsRefused) {
  std::string out;
  EXPECT_EQ(
      test::run_fsd("run --sim --headless --mission acceleration --track ../shared/tracks/epfl_skidpad.csv", &out), 2)
      << out;
  EXPECT_NE(out.find("no straight lane"), std::string::npos) << out;
}

TEST(RunRefusals, ALayoutWithOneBoundaryIsRefused) {
  // The left boundary of a loop alone: blue cones on a circle.
  std::string csv = "tag,x,y,direction,x_variance,y_variance,xy_covariance\ncar_start,20,0,1.5708,0,0,0\n";
  for (int k = 0; k < 40; ++k) {
    const double a = 2 * 3.14159265358979 * k / 40;
    csv += "blue," + std::to_string(18 * std::cos(a)) + "," + std::to_string(18 * std::sin(a)) + ",0,0,0,0\n";
  }
  const auto track = write("one_boundary.csv", csv);
  std::string out;
  EXPECT_EQ(test::run_fsd("run --sim --headless --until-finished --track " + track, &out), 2) << out;
  EXPECT_NE(out.find("one boundary only (40 left, 0 right"), std::string::npos) << out;
}

TEST(RunRefusals, AnUnwritableReportIsFoundBeforeTheRun) {
  std::string out;
  EXPECT_EQ(test::run_fsd("run --sim --headless --until-finished --report /nonexistent-dir/r.json", &out), 2) << out;
  EXPECT_NE(out.find("--report /nonexistent-dir/r.json: cannot be written"), std::string::npos) << out;
  EXPECT_EQ(out.find("driving"), std::string::npos) << out;  // refused before the run started
}

// A run refused for its usage writes nothing: the report path it was given does not appear (the writability check
// once left an empty file behind, which a script then took for a report).
TEST(RunRefusals, ARefusedRunLeavesNoReportFileBehind) {
  const auto report = test::scratch_path("refused_report.json");
  std::remove(report.c_str());
  std::string out;
  EXPECT_EQ(test::run_fsd("run --replay /nonexistent.mcap --sim --headless --report " + report, &out), 2) << out;
  EXPECT_NE(out.find("--replay takes the run from the recording"), std::string::npos) << out;
  EXPECT_FALSE(std::ifstream(report).good()) << report;
  EXPECT_EQ(test::run_fsd("run --sim --headless --rate 0 --report " + report, &out), 2) << out;
  EXPECT_FALSE(std::ifstream(report).good()) << report;
}

TEST(RunRefusals, TheVerdictNamesWhyARunFailed) {
  // Time runs out on lap 1: not finished, no stop, AS still Driving.
  const auto cfg = write("short.json", test::truth_sources({{"run", {{"max_sim_time", 12}}}}));
  const auto report = test::scratch_path("short_report.json");
  std::string out;
  EXPECT_EQ(test::run_fsd("run --sim --headless --until-finished --config " + cfg + " --report " + report, &out), 1)
      << out;
  const auto r = nlohmann::json::parse(std::ifstream(report));
  EXPECT_EQ(r["verdict"], "fail");
  const auto reasons = r["verdict_reasons"].dump();
  EXPECT_NE(reasons.find("not finished: 0 of 2 lap(s)"), std::string::npos) << reasons;
  EXPECT_NE(reasons.find("AS ended Driving, not Finished"), std::string::npos) << reasons;
  // A clean run passes with no reason.
  const auto fast = write("fast.json", kFast);
  const auto good = test::scratch_path("good_report.json");
  ASSERT_EQ(test::run_fsd("run --sim --headless --until-finished --mission acceleration --track "
                          "../shared/tracks/epfl_acceleration.csv --config " +
                              fast + " --report " + good,
                          &out),
            0)
      << out;
  const auto g = nlohmann::json::parse(std::ifstream(good));
  EXPECT_EQ(g["verdict"], "pass");
  EXPECT_TRUE(g["verdict_reasons"].empty());
  EXPECT_EQ(g["perception"]["source"], "truth");
  EXPECT_EQ(g["map"]["source"], "truth");
  // Rounded to the millisecond.
  const double t = g["laps"][0]["time_s"];
  EXPECT_DOUBLE_EQ(t, std::round(t * 1e3) / 1e3);
}

}  // namespace
}  // namespace fsd
