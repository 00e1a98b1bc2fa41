// `fsd localize` as a user runs it: on the AMZ 2017 logs it writes t_unix_s,east_m,north_m,yaw_rad in the ENU
// frame of the first fix (the log's own east/north columns are the truth for that frame); broken logs exit 2 with
// the file and line named.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "tests/daemon/fsd_process.hpp"
#include "tests/scratch_dir.hpp"

namespace fsd {
namespace {

const std::string kDir = "../shared/data/amz_2017/";

std::string args(const std::string& imu, const std::string& extra) {
  return "localize --imu " + imu + " --speed " + kDir + "optical_speed.csv --gps " + kDir + "gps.csv " + extra;
}

std::vector<std::vector<double>> read_rows(const std::string& path, std::string* header) {
  std::ifstream in(path);
  std::getline(in, *header);
  std::vector<std::vector<double>> rows;
  for (std::string line; std::getline(in, line);) {
    std::vector<double> r;
    std::stringstream ss(line);
    for (std::string f; std::getline(ss, f, ',');) r.push_back(std::stod(f));
    rows.push_back(r);
  }
  return rows;
}

// The log's east/north at the fix nearest t (the README: relative to the first fix).
std::pair<double, double> logged_fix(double t) {
  std::ifstream in(kDir + "gps.csv");
  std::string line;
  std::getline(in, line);
  double best = 1e9;
  std::pair<double, double> out;
  while (std::getline(in, line)) {
    double tt, lat, lon, e, n;
    char c;
    std::stringstream(line) >> tt >> c >> lat >> c >> lon >> c >> e >> c >> n;
    if (std::abs(tt - t) < best) {
      best = std::abs(tt - t);
      out = {e, n};
    }
  }
  return out;
}

TEST(LocalizeCli, WritesTheTrajectoryInTheFirstFixEnuFrame) {
  for (const std::string filter : {"ekf", "complementary"}) {
    const std::string out = test::scratch_path("traj_" + filter + ".csv");
    std::string text;
    ASSERT_EQ(
        test::run_fsd(args(kDir + "imu.csv", "--wheels " + kDir + "wheel_rpm.csv --filter " + filter + " --out " + out),
                      &text),
        0)
        << text;
    std::string header;
    const auto rows = read_rows(out, &header);
    EXPECT_EQ(header, "t_unix_s,east_m,north_m,yaw_rad");
    ASSERT_GT(rows.size(), 20000u) << "a pose per IMU sample from the heading's initialisation on";
    for (std::size_t i = 0; i < rows.size(); i += 1000) {
      ASSERT_EQ(rows[i].size(), 4u);
      const auto [e, n] = logged_fix(rows[i][0]);
      EXPECT_NEAR(rows[i][1], e, 2.0) << filter << " at " << rows[i][0];
      EXPECT_NEAR(rows[i][2], n, 2.0) << filter << " at " << rows[i][0];
    }
  }
}

TEST(LocalizeCli, BrokenLogsExitTwoNamingFileAndLine) {
  const auto write = [](const std::string& name, const std::string& body) {
    const std::string p = test::scratch_path(name);
    std::ofstream(p) << "t_unix_s,gyro_x_rad_s,gyro_y_rad_s,gyro_z_rad_s,acc_x_m_s2,acc_y_m_s2,acc_z_m_s2\n" << body;
    return p;
  };
  const std::string out = test::scratch_path("never.csv");
  struct Case {
    std::string file, expect;
  };
  const std::vector<Case> cases = {
      {write("bad_number.csv", "1.0,0,0,0,0,0,9.8\n1.005,0,0,x,0,0,9.8\n"),
       "bad_number.csv:3: column gyro_z_rad_s: 'x' is not a finite number"},
      {write("short_row.csv", "1.0,0,0,0,0,0,9.8\n1.005,0,0\n"), "short_row.csv:3: 3 fields, expected 7"},
      {write("backwards.csv", "1.0,0,0,0,0,0,9.8\n0.9,0,0,0,0,0,9.8\n"), "backwards.csv:3: time 0.9 does not increase"},
      {write("gap.csv", "1.0,0,0,0,0,0,9.8\n2.0,0,0,0,0,0,9.8\n"), "gap.csv:3: gap of 1 s since line 2"},
      {write("nan.csv", "1.0,0,0,nan,0,0,9.8\n"), "nan.csv:2: column gyro_z_rad_s: 'nan' is not a finite number"},
      {kDir + "gps.csv", "gps.csv:1: header 't_unix_s,lat_deg,lon_deg,east_m,north_m' is not the expected"},
      {test::scratch_path("missing.csv"), "missing.csv: cannot read"},
  };
  for (const auto& c : cases) {
    std::string text;
    EXPECT_EQ(test::run_fsd(args(c.file, "--out " + out), &text), 2) << text;
    EXPECT_NE(text.find(c.expect), std::string::npos) << "expected '" << c.expect << "' in: " << text;
  }
  std::string text;
  EXPECT_EQ(test::run_fsd(args(kDir + "imu.csv", "--gps-outage 30 --out " + out), &text), 2);
  EXPECT_NE(text.find("--gps-outage '30' is not A:B"), std::string::npos) << text;
  EXPECT_EQ(test::run_fsd(args(kDir + "imu.csv", "--gps-outage 40:30 --out " + out), &text), 2);
  EXPECT_EQ(test::run_fsd(args(kDir + "imu.csv", "--filter kalman --out " + out), &text), 2);
  EXPECT_FALSE(std::ifstream(out).good()) << "no trajectory from bad input";
}

}  // namespace
}  // namespace fsd
