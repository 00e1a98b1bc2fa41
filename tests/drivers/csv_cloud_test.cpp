// CSV point clouds as `fsd detect` reads them: both layouts with and without a header, lidar-dump's columns by
// name, non-finite rows dropped and counted, and every kind of bad input rejected naming the line.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <numbers>

#include "drivers/cloud/csv_cloud.hpp"
#include "tests/scratch_dir.hpp"

namespace fsd {
namespace {

std::string error_of(const std::string& text, const CsvCloudLimits& limits = {}) {
  try {
    parse_csv_cloud(text, "t.csv", limits);
  } catch (const CloudError& e) {
    return e.what();
  }
  return "";
}

TEST(CsvCloud, ReadsXyzAndIntensityWithOrWithoutHeader) {
  const auto plain = parse_csv_cloud("1,2,3\n4.5,-5,0.25\n", "t.csv");
  ASSERT_EQ(plain.scan.points.size(), 2u);
  EXPECT_FALSE(plain.header);
  EXPECT_FALSE(plain.has_intensity);
  EXPECT_FLOAT_EQ(plain.scan.points[1].x, 4.5f);
  EXPECT_FLOAT_EQ(plain.scan.points[1].y, -5.0f);
  EXPECT_FLOAT_EQ(plain.scan.points[1].z, 0.25f);
  // Distance and azimuth (clockwise from +x, as the VLP-16 decoder gives them) from the frame origin.
  EXPECT_NEAR(plain.scan.points[0].distance, std::sqrt(14.0), 1e-6);
  EXPECT_NEAR(plain.scan.points[0].azimuth, 2 * std::numbers::pi - std::atan2(2.0, 1.0), 1e-6);

  const auto with = parse_csv_cloud("# a comment\r\nX, Y, Z, Intensity\r\n\r\n1,2,3,40\r\n", "t.csv");
  ASSERT_EQ(with.scan.points.size(), 1u);
  EXPECT_TRUE(with.header);
  EXPECT_TRUE(with.has_intensity);
  EXPECT_FLOAT_EQ(with.scan.points[0].intensity, 40.0f);
}

TEST(CsvCloud, ReadsLidarDumpColumnsByName) {
  const auto c = parse_csv_cloud(
      "t_us,laser,azimuth_deg,distance_m,intensity,x,y,z\n"
      "332917037.000,0,250.3500,3.336,44,-1.0836,3.0347,-0.8522\n"
      "332917039.304,1,250.3583,3.592,7,-1.2072,3.3825,0.0620\n",
      "dump.csv");
  ASSERT_EQ(c.scan.points.size(), 2u);
  EXPECT_TRUE(c.has_lasers && c.has_times && c.has_intensity);
  EXPECT_EQ(c.scan.points[1].ring, 1);
  EXPECT_FLOAT_EQ(c.scan.points[1].intensity, 7.0f);
  EXPECT_FLOAT_EQ(c.scan.points[0].x, -1.0836f);
  EXPECT_NEAR(c.scan.points[1].t - c.scan.points[0].t, 2.304e-6, 1e-9);
}

TEST(CsvCloud, DropsAndCountsNonFiniteRows) {
  const auto c = parse_csv_cloud("1,2,3\nnan,2,3\n1,inf,3\n1,2,-inf\n1,2,1e9\n4,5,6\n", "t.csv");
  EXPECT_EQ(c.rows, 6u);
  EXPECT_EQ(c.invalid, 4u);
  EXPECT_EQ(c.scan.points.size(), 2u);
  // An intensity beyond a float (found by the fuzzer: it became inf) is no data either.
  const auto i =
      parse_csv_cloud("1,2,3,8888888888888888888888888888888888888888888888836\n1,2,3,nan\n4,5,6,7\n", "t.csv");
  EXPECT_EQ(i.invalid, 2u);
  ASSERT_EQ(i.scan.points.size(), 1u);
  EXPECT_FLOAT_EQ(i.scan.points[0].intensity, 7.0f);
}

TEST(CsvCloud, RejectsBadInputNamingTheLine) {
  EXPECT_NE(error_of(""), "");
  EXPECT_NE(error_of("x,y,z\n").find("no valid point"), std::string::npos);
  EXPECT_NE(error_of("nan,1,2\nnan,3,4\n").find("no valid point"), std::string::npos);
  EXPECT_NE(error_of("1,2\n").find("t.csv:1:"), std::string::npos);
  EXPECT_NE(error_of("1,2,3\n1,2,3,4\n").find("t.csv:2: expected 3 fields"), std::string::npos);
  EXPECT_NE(error_of("1,2,3\n1,abc,3\n").find("t.csv:2: y is not a number"), std::string::npos);
  EXPECT_NE(error_of("1,2,3\n1,,3\n").find("t.csv:2:"), std::string::npos);
  EXPECT_NE(error_of("a,b,c\n1,2,3\n").find("needs columns x, y and z"), std::string::npos);
  EXPECT_NE(error_of("x,y,z,x\n1,2,3,4\n").find("appears twice"), std::string::npos);
  EXPECT_NE(error_of("x,y,z,laser\n1,2,3,1.5\n").find("laser must be an integer"), std::string::npos);
  EXPECT_NE(error_of("1,2,3,4,5,6,7,8,9,10,11,12,13,14,15,16,17\n").find("more than 16 fields"), std::string::npos);
  EXPECT_NE(error_of(std::string("1,2,3\0,4\n", 9)).find("t.csv:1:"), std::string::npos);
}

TEST(CsvCloud, BoundsThePointsAndTheFileSize) {
  CsvCloudLimits limits;
  limits.max_points = 3;
  EXPECT_NO_THROW(parse_csv_cloud("1,1,1\n2,2,2\n3,3,3\n", "t.csv", limits));
  EXPECT_NE(error_of("1,1,1\n2,2,2\n3,3,3\n4,4,4\n", limits).find("more than 3 points"), std::string::npos);

  const auto path = test::scratch_path("big.csv");
  { std::ofstream(path) << "1,2,3\n"; }
  limits.max_bytes = 4;
  try {
    load_csv_cloud(path, limits);
    FAIL() << "a file over the byte limit was read";
  } catch (const CloudError& e) {
    EXPECT_NE(std::string(e.what()).find("bytes"), std::string::npos);
  }
  EXPECT_THROW(load_csv_cloud(test::scratch_path("missing.csv")), CloudError);
}

}  // namespace
}  // namespace fsd
