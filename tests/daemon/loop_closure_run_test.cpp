// Loop closure in the Stack (issue #17), end to end: `fsd run --sim --headless --until-finished --laps 2` with
// run.localization_source = lidar_odometry, truth perception and the virtual VLP-16, with loop closure and without
// (localization.loop_closure.enabled). The LiDAR odometry drifts 0.3–0.6 % of the distance; without loop closure the
// cones seen again at lap 1's end are mapped 1–2.5 m from their copies of the start. Judged by the scorecard against
// the virtual car's truth (docs/scorecard.md): the pose's error where the loop closed, the map's RMSE and ghosts.
// The runs are not clean: lap 2 follows the recorded lap on the odometry alone, which drifts again over the lap
// and lags above 8 m/s (docs/localization.md has the figures); the cones hit are measured there, not asserted.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "tests/daemon/sim_report.hpp"

namespace fsd {
namespace {

using nlohmann::json;

json lidar_odometry_run(const std::string& name, const std::string& track, bool loop_closure) {
  return test::sim_report(name,
                          {{"sim", {{"enable_camera", false}}},
                           {"run", {{"localization_source", "lidar_odometry"}, {"max_sim_time", 150.0}}},
                           {"localization", {{"loop_closure", {{"enabled", loop_closure}}}}}},
                          "--laps 2 --track ../shared/tracks/" + track + ".csv", /*must_pass=*/false);
}

TEST(LoopClosureRun, TheLapsLoopClosesOnceNearTheStartAndTheMapIsOneMapAgain) {
  const json off = lidar_odometry_run("loop_closure_off", "epfl_track_2", false);
  const json on = lidar_odometry_run("loop_closure_on", "epfl_track_2", true);
  ASSERT_TRUE(off.is_object() && on.is_object());
  ASSERT_TRUE(off["odometry"].contains("loop_closures")) << off["odometry"].dump();
  EXPECT_TRUE(off["odometry"]["loop_closures"].empty());

  const json& closures = on["odometry"]["loop_closures"];
  ASSERT_GE(closures.size(), 1u) << on["odometry"].dump();
  ASSERT_LE(closures.size(), 2u) << closures.dump();  // once per lap at most
  for (std::size_t i = 0; i < closures.size(); ++i) {
    const json& c = closures[i];
    EXPECT_EQ(c["lap"], int(i) + 1);
    EXPECT_GE(c["pairs"].get<int>(), 6) << c.dump();
    // Most of the lap's drift taken away (measured 1.07 m -> 0.14 m).
    EXPECT_LT(c["error_after_m"].get<double>(), 0.3) << c.dump();
    EXPECT_LT(c["error_after_m"].get<double>(), 0.5 * c["error_before_m"].get<double>()) << c.dump();
  }
  const json& first = closures[0];
  EXPECT_GT(first["error_before_m"].get<double>(), 0.5) << first.dump();  // worth closing
  EXPECT_GT(first["cones_merged"].get<int>(), 0) << first.dump();
  // Never early: lap 1 takes 45.8 s from the start at 6 s (the car stands, then drives off); the loop closes as
  // the start's cones come back into view, before lap 1's line.
  ASSERT_GE(on["laps"].size(), 1u);
  const double lap1_end = 6.0 + on["laps"][0]["time_s"].get<double>();
  EXPECT_GT(first["time_s"].get<double>(), lap1_end - 10.0) << first.dump();
  EXPECT_LT(first["time_s"].get<double>(), lap1_end + 2.0) << first.dump();

  // One map again: measured RMSE 0.321 -> 0.198 m, ghosts 478 -> 104, missed 159 -> 0.
  const json &m_off = off["map"], &m_on = on["map"];
  EXPECT_LT(m_on["rmse_m"].get<double>(), 0.75 * m_off["rmse_m"].get<double>()) << m_on.dump() << m_off.dump();
  EXPECT_LT(m_on["ghosts"].get<int>(), m_off["ghosts"].get<int>() / 2) << m_on.dump() << m_off.dump();
  EXPECT_LT(m_on["missed"].get<int>(), m_off["missed"].get<int>()) << m_on.dump() << m_off.dump();
  // The odometry's own drift is reported uncorrected either way (its figure, not the driven pose's).
  EXPECT_LT(on["odometry"]["drift_pct"].get<double>(), 1.0);
}

}  // namespace
}  // namespace fsd
