#pragma once
// `fsd localize` without the command line: sensor logs in the ../shared/data/amz_2017 CSV format turned into the
// fusion's measurements, run through one filter in time order, with GNSS withheld over an optional outage window.
// The map frame is the local ENU frame of the first GNSS fix (from its latitude and longitude).
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "localization/fusion/fusion_filter.hpp"

namespace fsd {

struct LocalizeLogs {
  std::vector<fusion::ImuSample> imu;
  std::vector<fusion::BodySpeed> optical;
  std::vector<fusion::BodySpeed> wheels;
  std::vector<fusion::GnssFix> gnss;  // ENU of the first fix, quality 1 (the logs carry none)
};

struct LocalizeLogFiles {
  std::filesystem::path imu, speed, wheels, gps;  // wheels and gps may be empty
};

struct LocalizeOptions {
  std::string filter = "ekf";
  fusion::FusionConfig config;
  std::optional<std::pair<double, double>> gnss_outage;  // s after the first fix: GNSS ignored in [A, B]
  Vec2 optical_lever{-0.41, 0.27};                       // the Correvit from the IMU (the logs' reference point)
  double wheel_rpm_per_m_s = 621.0;                      // motor rpm per m/s of wheel speed
};

// Throws SensorCsvError (from drivers/logs/sensor_csv.hpp) naming the file and line.
LocalizeLogs load_localize_logs(const LocalizeLogFiles& files, const LocalizeOptions& options);

// The state after every IMU sample once the filter has a position and a heading.
std::vector<fusion::LocalizationState> run_localize(const LocalizeLogs& logs, const LocalizeOptions& options);

// t_unix_s,east_m,north_m,yaw_rad with a header; false when the file cannot be written.
bool write_trajectory_csv(const std::filesystem::path& file, const std::vector<fusion::LocalizationState>& states);

}  // namespace fsd
