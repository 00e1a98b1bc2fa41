// The laser table: built-in values, the shared calibration CSV, rejection of bad files, custom firing order.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <numbers>
#include <string>

#include "common/wire/vlp16_format.hpp"
#include "drivers/vlp16/decoder.hpp"
#include "drivers/vlp16/laser_table.hpp"
#include "tests/drivers/vlp16_test_packets.hpp"
#include "tests/scratch_dir.hpp"

namespace fsd {
namespace {

std::string write_temp(const std::string& name, const std::string& text) {
  const std::string path = test::scratch_path(name);
  std::ofstream(path) << text;
  return path;
}

TEST(Vlp16LaserTable, BuiltinMatchesTheManual) {
  const auto t = LaserTable::builtin();
  // VLP-16 manual table 9-1: channels alternate -15°, +1°, -13°, +3°, ... with offsets of ±11.2 mm down to 0.7 mm.
  EXPECT_NEAR(t[0].elevation, -15 * std::numbers::pi / 180, 1e-12);
  EXPECT_NEAR(t[15].elevation, 15 * std::numbers::pi / 180, 1e-12);
  EXPECT_NEAR(t[14].elevation, -1 * std::numbers::pi / 180, 1e-12);
  EXPECT_DOUBLE_EQ(t[0].vertical_offset, 0.0112);
  EXPECT_DOUBLE_EQ(t[15].vertical_offset, -0.0112);
  for (std::size_t i = 0; i < 16; ++i) {
    EXPECT_EQ(t[i].ring, wire::vlp16::ring_of_laser(i)) << "laser " << i;
    EXPECT_EQ(t[i].firing_slot, i);
    EXPECT_NEAR(t[i].cos_elevation, std::cos(t[i].elevation), 1e-15);
  }
}

TEST(Vlp16LaserTable, SharedCalibrationFileEqualsTheBuiltinTable) {
  const auto file = LaserTable::from_csv("../shared/data/vlp16/vlp16_lasers.csv");
  const auto builtin = LaserTable::builtin();
  for (std::size_t i = 0; i < 16; ++i) {
    EXPECT_DOUBLE_EQ(file[i].elevation, builtin[i].elevation) << i;
    EXPECT_DOUBLE_EQ(file[i].vertical_offset, builtin[i].vertical_offset) << i;
    EXPECT_EQ(file[i].firing_slot, builtin[i].firing_slot) << i;
    EXPECT_EQ(file[i].ring, builtin[i].ring) << i;
  }
  EXPECT_NO_THROW(LaserTable::load(""));
}

TEST(Vlp16LaserTable, RejectsBadFilesNamingFileAndLine) {
  const std::string header = "laser_id,vert_angle_deg,vert_offset_correction_m\n";
  std::string rows;
  for (int i = 0; i < 16; ++i) rows += std::to_string(i) + "," + std::to_string(i - 8) + ",0.001\n";

  const auto expect_error = [](const std::string& path, const std::string& fragment) {
    try {
      LaserTable::from_csv(path);
      ADD_FAILURE() << "no error for " << path;
    } catch (const LaserTableError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(path), std::string::npos) << what;
      EXPECT_NE(what.find(fragment), std::string::npos) << what;
    }
  };
  EXPECT_NO_THROW(LaserTable::from_csv(write_temp("lasers_ok.csv", header + rows)));
  expect_error(write_temp("lasers_short.csv", header + "0,-15,0.01\n"), "expected 16 lasers");
  expect_error(write_temp("lasers_dup.csv", header + rows + "3,1,0\n"), "line 18: laser_id 3 appears twice");
  expect_error(write_temp("lasers_nan.csv", header + "0,abc,0\n"), "line 2: vert_angle_deg is not a number");
  expect_error(write_temp("lasers_id.csv", header + "16,1,0\n"), "laser_id must be an integer 0..15");
  expect_error(write_temp("lasers_cols.csv", header + "0,1\n"), "expected 3 columns");
  expect_error(write_temp("lasers_header.csv", "id,angle\n"), "header must name");
  expect_error(test::scratch_path("no_such_lasers.csv"), "cannot open");
}

TEST(Vlp16LaserTable, FiringOrderFromTheFileSetsFiringTimeAndInterpolation) {
  // Same elevations, but the file says laser 0 fires last in its sequence.
  std::string text = "laser_id,vert_angle_deg,vert_offset_correction_m,firing_order_in_sequence\n";
  const auto& spec = wire::vlp16::kLaserTable;
  for (int i = 0; i < 16; ++i)
    text += std::to_string(i) + "," + std::to_string(spec[static_cast<std::size_t>(i)].elevation_deg) + "," +
            std::to_string(spec[static_cast<std::size_t>(i)].vertical_offset_m) + "," + std::to_string(15 - i) + "\n";
  const auto table = LaserTable::from_csv(write_temp("lasers_reversed.csv", text));
  EXPECT_EQ(table[0].firing_slot, 15);
  EXPECT_EQ(table[0].ring, 0);

  PacketDecoder d(table, 0.5, 130);
  test::Vlp16PacketBytes p(0, 1000, 40);
  p.channel(0, 0, 0, 1000, 1);
  std::vector<Vlp16Return> out;
  ASSERT_EQ(d.decode(p.bytes(), out), PacketStatus::Ok);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_NEAR(out[0].firing_offset_us, 15 * 2.304, 1e-9);
  EXPECT_NEAR(out[0].azimuth_deg, 10.0 + 0.40 * 15 * 2.304 / 110.592, 1e-9);
}

}  // namespace
}  // namespace fsd
