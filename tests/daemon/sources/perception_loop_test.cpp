// The car driving on its own perception, as a user runs it: `fsd run --sim --headless --until-finished` with every
// sensor of the virtual car (LiDAR ray casting, camera rendering, distractors: tyres, stacks, posts, fences) and
// run.perception_source = lidar_camera or lidar, truth localization. The scorecard holds the detections of every
// frame against the simulated world's standing cones (daemon/perception_score) and the map against the layout:
// the issue's figures (#16), on a trackdrive the perception was not tuned on.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "tests/daemon/sim_report.hpp"

namespace fsd {
namespace {

using nlohmann::json;

// On the true pose, so that what is measured is perception's alone.
json drive(const std::string& source, const std::string& track) {
  return test::sim_report("perception_loop_" + source,
                          {{"run", {{"perception_source", source}, {"localization_source", "truth"}}}},
                          "--laps 2 --track ../shared/tracks/" + track + ".csv");
}

TEST(PerceptionLoop, LidarAndCameraDriveTwoCleanLapsWithTheIssuesFigures) {
  const json r = drive("lidar_camera", "epfl_track_3");
  ASSERT_TRUE(r.is_object());
  EXPECT_EQ(r["verdict"], "pass") << r["verdict_reasons"].dump();
  EXPECT_EQ(r["cones_hit"], 0);
  const json& p = r["perception"];
  EXPECT_EQ(p["source"], "lidar_camera");
  EXPECT_GT(p["frames"].get<int>(), 500);  // 10 Hz over the whole run
  EXPECT_GE(p["precision"].get<double>(), 0.99) << p.dump();
  EXPECT_GE(p["recall_15m"].get<double>(), 0.97) << p.dump();
  EXPECT_GE(p["recall_20m"].get<double>(), 0.85) << p.dump();
  EXPECT_LE(p["position_rmse_m"].get<double>(), 0.08) << p.dump();
  EXPECT_GE(p["verified_colour_accuracy_12m"].get<double>(), 0.98) << p.dump();
  EXPECT_GT(p["verified_share_12m"].get<double>(), 0.2) << p.dump();  // the camera sees a 70° cone ahead
  const json& m = r["map"];
  EXPECT_EQ(m["missed"], 0) << m.dump();
  EXPECT_LE(m["rmse_m"].get<double>(), 0.10) << m.dump();
  EXPECT_GE(m["colour_accuracy"].get<double>(), 0.98) << m.dump();
}

TEST(PerceptionLoop, TheLidarAloneColoursTheNearConesFromTheirReflectivity) {
  const json r = drive("lidar", "epfl_track_4");
  ASSERT_TRUE(r.is_object());
  EXPECT_EQ(r["verdict"], "pass") << r["verdict_reasons"].dump();
  const json& p = r["perception"];
  EXPECT_EQ(p["source"], "lidar");
  EXPECT_EQ(p["verified_share_12m"], 0.0);  // no camera stage
  EXPECT_GE(p["colour_accuracy_6m"].get<double>(), 0.90) << p.dump();
  EXPECT_GE(p["named_colour_accuracy_12m"].get<double>(), 0.98) << p.dump();
  EXPECT_GE(p["recall_15m"].get<double>(), 0.97) << p.dump();
}

}  // namespace
}  // namespace fsd
