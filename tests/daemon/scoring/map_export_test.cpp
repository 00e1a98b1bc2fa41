// `fsd run --map-out FILE`: the cone map at the end of a run as a track file. Compared with the layout the virtual
// car drove (its true cones), and driven again as a layout of its own.
#include <gtest/gtest.h>

#include <fstream>

#include <nlohmann/json.hpp>

#include "common/track.hpp"
#include "daemon/scoring/map_export.hpp"
#include "tests/daemon/fsd_process.hpp"
#include "tests/scratch_dir.hpp"
#include "tests/truth_sources.hpp"

namespace fsd {
namespace {

TEST(MapExport, ConesWithoutABoundaryColourAreCountedNotWritten) {
  std::vector<Cone> map(3);
  map[0].position = Vec3(1, 2, 0);
  map[0].colour = ConeColour::Blue;
  map[1].position = Vec3(1, -2, 0);
  map[1].colour = ConeColour::Unknown;
  map[2].position = Vec3(5, -2, 0);
  map[2].colour = ConeColour::Yellow;
  const MapExport m = map_as_track(map, Pose2{0.5, 0.25, 1.0}, ColourConvention::named("fsg"), "m");
  EXPECT_EQ(m.without_role, 1u);
  const Track back = parse_track(format_track(m.track), "m.csv");
  ASSERT_EQ(back.cones.size(), 2u);
  EXPECT_EQ(back.cones[0].role, ConeRole::Left);
  EXPECT_EQ(back.cones[1].role, ConeRole::Right);
  EXPECT_NEAR(back.cones[1].position.x(), 5.0, 1e-4);
  EXPECT_NEAR(back.start.yaw, 1.0, 1e-6);
  EXPECT_THROW(write_map_csv("/nonexistent_dir/m.csv", m), std::invalid_argument);
}

TEST(MapExport, ALapOneMapIsTheLayoutDrivenAndDrivesAgain) {
  const std::string track = "../shared/tracks/epfl_track_1.csv";
  const auto cfg = test::scratch_path("map_out_cfg.json");
  std::ofstream(cfg) << test::truth_sources();
  const auto map_csv = test::scratch_path("lap1_map.csv");
  std::string out;
  ASSERT_EQ(test::run_fsd("run --sim --headless --until-finished --laps 1 --config " + cfg + " --track " + track +
                              " --map-out " + map_csv,
                          &out),
            0)
      << out;
  const Track truth = load_track(track);
  const Track mapped = load_track(map_csv);
  // The start row is where the car started; every true cone is in the map, at its place, with its role.
  EXPECT_LT((Vec2(mapped.start.x, mapped.start.y) - Vec2(truth.start.x, truth.start.y)).norm(), 0.1);
  std::size_t found = 0;
  for (const auto& t : truth.cones) {
    for (const auto& m : mapped.cones)
      if ((m.position - t.position).norm() < 0.15 && m.role == t.role) {
        ++found;
        break;
      }
  }
  EXPECT_GE(static_cast<double>(found), 0.98 * static_cast<double>(truth.cones.size()));
  EXPECT_LE(mapped.cones.size(), truth.cones.size() + 2);  // no more than a couple of ghosts
  // Reused: the map is a layout the virtual car drives, start to finish.
  const auto report = test::scratch_path("map_reuse.json");
  EXPECT_EQ(test::run_fsd("run --sim --headless --until-finished --laps 1 --config " + cfg + " --track " + map_csv +
                              " --report " + report,
                          &out),
            0)
      << out;
  // Refused before the run when it cannot be written.
  EXPECT_EQ(test::run_fsd("run --sim --headless --laps 1 --map-out /nonexistent_dir/m.csv", &out), 2) << out;
  EXPECT_NE(out.find("--map-out /nonexistent_dir/m.csv: cannot be written"), std::string::npos) << out;
}

}  // namespace
}  // namespace fsd
