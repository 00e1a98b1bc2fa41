// Track loader on every shared track file. Expected counts were counted independently with
// `grep -c '^blue,' FILE` (and likewise per tag) less the rows that repeat an earlier row's x,y (a cone listed
// twice is one cone; counted with awk on the x,y columns), and the start rows read with `grep car_start`.
#include <gtest/gtest.h>

#include <filesystem>

#include "common/track.hpp"

namespace fsd {
namespace {

struct Expected {
  const char* name;
  std::size_t blue, yellow, orange, big_orange;
  int repeated;  // rows dropped as repeats
  double x, y, yaw;
};

constexpr Expected kTracks[] = {
    {"amz_fssim_acceleration", 14, 14, 41, 8, 1, -2.0000, 0.0000, 0.087000},
    {"amz_fssim_skidpad", 29, 29, 11, 4, 1, -16.5000, 0.0000, 0.000000},
    {"amz_fssim_thin", 47, 42, 0, 4, 1, 0.0000, 0.0000, 0.000000},
    {"epfl_21_05_2023", 28, 28, 0, 4, 0, 0.0000, 0.0000, -1.570796},
    {"epfl_VSV", 23, 23, 0, 0, 0, 0.0000, 0.0000, 1.570796},
    {"epfl_VSV_XL", 23, 23, 0, 0, 0, 0.0000, 0.0000, 1.570796},
    {"epfl_VSV_XS", 17, 17, 0, 0, 0, 0.0000, 0.0000, 1.570796},
    {"epfl_acceleration", 14, 14, 42, 8, 0, 0.0000, 0.0000, 1.570796},
    {"epfl_acceleration_4_5m", 16, 16, 46, 8, 0, 0.0000, 0.0000, 1.570796},
    {"epfl_acceleration_4m", 18, 18, 52, 8, 0, 0.0000, 0.0000, 1.570796},
    {"epfl_acceleration_5_5m", 13, 13, 38, 8, 0, 0.0000, 0.0000, 1.570796},
    {"epfl_acceleration_large", 13, 13, 42, 8, 2, 0.0000, 0.0000, 1.570796},
    {"epfl_autoX_Vaudoise_Sponso", 24, 29, 0, 4, 18, 0.0000, -1.5000, 1.570796},
    {"epfl_ebs_test_fss", 13, 13, 42, 8, 2, 0.0000, 0.0000, 1.570796},
    {"epfl_fsds_competition_1", 85, 85, 0, 4, 0, -0.2740, 5.5719, 1.570796},
    {"epfl_fsds_competition_2", 115, 115, 0, 4, 0, -0.1899, 6.4212, 1.470796},
    {"epfl_fsds_competition_3", 90, 90, 0, 4, 0, 0.2114, 9.1460, 1.581541},
    {"epfl_fsds_default", 96, 96, 0, 4, 0, 1.2930, 9.1173, 1.575284},
    {"epfl_short_skidpad", 29, 29, 18, 4, 0, 0.0000, 0.0000, 1.570796},
    {"epfl_skidpad", 30, 30, 18, 4, 0, 0.0000, 0.0000, 1.570796},
    {"epfl_skidpad_minimalist", 30, 30, 0, 4, 0, 0.0000, 0.0000, 1.570796},
    {"epfl_skidpad_reversed", 30, 30, 18, 4, 0, 0.0000, 0.0000, 1.570796},
    {"epfl_skidpad_v2", 30, 30, 18, 4, 0, 0.0000, 0.0000, 1.570796},
    {"epfl_track_1", 102, 96, 0, 4, 0, 0.0000, 0.0000, 1.570796},
    {"epfl_track_2", 117, 111, 0, 4, 0, 0.0000, 0.0000, 1.570796},
    {"epfl_track_3", 147, 141, 0, 4, 0, 0.0000, 0.0000, 1.570796},
    {"epfl_track_4", 139, 132, 0, 4, 0, 0.0000, 0.0000, 1.570796},
    {"epfl_track_5", 109, 103, 0, 4, 0, 0.0000, 0.0000, 1.570796},
};

TEST(TrackLoader, EverySharedTrackHasTheCountedConesAndStart) {
  std::size_t seen = 0;
  for (const auto& e : kTracks) {
    SCOPED_TRACE(e.name);
    const Track t = load_track(std::string("../shared/tracks/") + e.name + ".csv");
    EXPECT_EQ(t.name, e.name);
    EXPECT_EQ(t.count(ConeRole::Left), e.blue);
    EXPECT_EQ(t.count(ConeRole::Right), e.yellow);
    EXPECT_EQ(t.count(ConeRole::Other), e.orange);
    EXPECT_EQ(t.count(ConeRole::Timing), e.big_orange);
    EXPECT_EQ(t.cones.size(), e.blue + e.yellow + e.orange + e.big_orange);
    EXPECT_EQ(t.duplicates_dropped, e.repeated);
    EXPECT_NEAR(t.start.x, e.x, 1e-9);
    EXPECT_NEAR(t.start.y, e.y, 1e-9);
    EXPECT_NEAR(t.start.yaw, e.yaw, 1e-9);
    ++seen;
  }
  // Every file in the shared folder is in the table: a new track must be counted too.
  std::size_t files = 0;
  for (const auto& f : std::filesystem::directory_iterator("../shared/tracks"))
    if (f.path().extension() == ".csv") ++files;
  EXPECT_EQ(files, seen);
}

TEST(TrackLoader, ColourConventionMapsRolesToPhysicalColours) {
  const Track fsg = load_track("../shared/tracks/epfl_track_1.csv");
  const Track fsac = load_track("../shared/tracks/epfl_track_1.csv", ColourConvention::named("fsac"));
  ASSERT_EQ(fsg.cones.size(), fsac.cones.size());
  for (std::size_t i = 0; i < fsg.cones.size(); ++i) {
    EXPECT_EQ(fsg.cones[i].role, fsac.cones[i].role);
    if (fsg.cones[i].role == ConeRole::Left) {
      EXPECT_EQ(fsg.cones[i].colour, ConeColour::Blue);
      EXPECT_EQ(fsac.cones[i].colour, ConeColour::Red);
    }
    if (fsg.cones[i].role == ConeRole::Right) {
      EXPECT_EQ(fsg.cones[i].colour, ConeColour::Yellow);
      EXPECT_EQ(fsac.cones[i].colour, ConeColour::Blue);
    }
  }
  EXPECT_EQ(fsac.convention.role_of(ConeColour::Yellow), ConeRole::Timing);
  EXPECT_EQ(fsg.convention.role_of(ConeColour::Yellow), ConeRole::Right);
  EXPECT_THROW(ColourConvention::named("rainbow"), std::invalid_argument);
}

TEST(TrackLoader, FirstConeOfTrack1HasTheFileValues) {
  const Track t = load_track("../shared/tracks/epfl_track_1.csv");
  // Line 3 of the file: blue,-10.6591,-15.9889,0,0,0,0
  EXPECT_EQ(t.cones.front().role, ConeRole::Left);
  EXPECT_DOUBLE_EQ(t.cones.front().position.x(), -10.6591);
  EXPECT_DOUBLE_EQ(t.cones.front().position.y(), -15.9889);
}

std::string error_of(const std::string& text) {
  try {
    parse_track(text, "bad.csv");
  } catch (const TrackError& e) {
    return e.what();
  }
  return "no error";
}

TEST(TrackLoader, MalformedFilesGiveLineNumbers) {
  const std::string header = "tag,x,y,direction,x_variance,y_variance,xy_covariance\n";
  const std::string start = "car_start,0,0,1.57,0,0,0\n";
  EXPECT_EQ(error_of("tag,x,direction\nblue,1,2\n"), "bad.csv:1: missing column 'y' in header");
  EXPECT_EQ(error_of(header + start + "blue,1.0,abc,0,0,0,0\n"), "bad.csv:3: bad number 'abc' in column 'y'");
  EXPECT_EQ(error_of(header + start + "blue,1.0,2.0x,0,0,0,0\n"), "bad.csv:3: bad number '2.0x' in column 'y'");
  EXPECT_EQ(error_of(header + start + "\nblue,1.0\n"), "bad.csv:4: missing value for column 'y'");
  EXPECT_EQ(error_of(header + start + "green,1,2,0,0,0,0\n"),
            "bad.csv:3: unknown tag 'green' (blue, yellow, orange, big_orange, car_start)");
  EXPECT_EQ(error_of(header + start + start + "blue,1,2,0,0,0,0\n"), "bad.csv:3: second car_start row");
  EXPECT_EQ(error_of(header + "blue,1,2,0,0,0,0\n"), "bad.csv: no car_start row");
  EXPECT_EQ(error_of(""), "bad.csv: empty file, expected a header line");
  EXPECT_EQ(error_of(header + "blue,nan,2,0,0,0,0\n" + start), "bad.csv:2: bad number 'nan' in column 'x'");
  EXPECT_THROW(load_track("../shared/tracks/does_not_exist.csv"), TrackError);
}

TEST(TrackLoader, AcceptsCrLfAndOptionalCovarianceColumns) {
  const Track t = parse_track("tag,x,y,direction\r\ncar_start,1,2,0.5\r\nyellow,3,4,0\r\n", "mini.csv");
  ASSERT_EQ(t.cones.size(), 1u);
  EXPECT_EQ(t.cones[0].role, ConeRole::Right);
  EXPECT_DOUBLE_EQ(t.start.yaw, 0.5);
}

TEST(TrackLoader, ARowRepeatingAConeIsOneCone) {
  // Two rows 5 mm apart are one physical cone (the first row's role wins); 5 cm apart are two cones.
  const Track t =
      parse_track("tag,x,y,direction\ncar_start,0,0,0\nyellow,3,4,0\nblue,3.005,4,0\nyellow,3.05,4,0\n", "repeat.csv");
  ASSERT_EQ(t.cones.size(), 2u);
  EXPECT_EQ(t.cones[0].role, ConeRole::Right);
  EXPECT_DOUBLE_EQ(t.cones[1].position.x(), 3.05);
  EXPECT_EQ(t.duplicates_dropped, 1);
}

}  // namespace
}  // namespace fsd
