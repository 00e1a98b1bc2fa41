#include "daemon/cli/localize_replay.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>

#include "common/geodesy.hpp"
#include "drivers/logs/sensor_csv.hpp"

namespace fsd {

namespace {

// The IMU and the speed sensors feed dead reckoning: a longer silence is a broken log, not an outage.
constexpr double kMaxMotionGap = 0.5;  // s

SensorCsvSpec spec(std::vector<std::string> columns, double max_gap) {
  SensorCsvSpec s;
  s.columns = std::move(columns);
  s.max_gap_s = max_gap;
  return s;
}

}  // namespace

LocalizeLogs load_localize_logs(const LocalizeLogFiles& files, const LocalizeOptions& options) {
  LocalizeLogs logs;
  const auto imu = load_sensor_csv(files.imu, spec({"t_unix_s", "gyro_x_rad_s", "gyro_y_rad_s", "gyro_z_rad_s",
                                                    "acc_x_m_s2", "acc_y_m_s2", "acc_z_m_s2"},
                                                   kMaxMotionGap));
  for (std::size_t i = 0; i < imu.rows(); ++i)
    logs.imu.push_back(
        {imu.at(i, 0), Vec3(imu.at(i, 1), imu.at(i, 2), imu.at(i, 3)), Vec3(imu.at(i, 4), imu.at(i, 5), imu.at(i, 6))});

  const auto speed = load_sensor_csv(files.speed, spec({"t_unix_s", "vx_m_s", "vy_m_s"}, kMaxMotionGap));
  for (std::size_t i = 0; i < speed.rows(); ++i) {
    fusion::BodySpeed b;
    b.t = speed.at(i, 0);
    b.source = fusion::BodySpeed::Source::Optical;
    b.vx = speed.at(i, 1);
    b.vy = speed.at(i, 2);
    b.lever = options.optical_lever;
    logs.optical.push_back(b);
  }

  if (!files.wheels.empty()) {
    const auto w =
        load_sensor_csv(files.wheels, spec({"t_unix_s", "fl_rpm", "fr_rpm", "rl_rpm", "rr_rpm"}, kMaxMotionGap));
    for (std::size_t i = 0; i < w.rows(); ++i) {
      // The mean of the four wheels is the speed at the centre between the axles (left and right cancel in a turn).
      fusion::BodySpeed b;
      b.t = w.at(i, 0);
      b.source = fusion::BodySpeed::Source::Wheels;
      b.vx = (w.at(i, 1) + w.at(i, 2) + w.at(i, 3) + w.at(i, 4)) / (4.0 * options.wheel_rpm_per_m_s);
      b.has_vy = false;
      logs.wheels.push_back(b);
    }
  }

  if (!files.gps.empty()) {
    const auto g = load_sensor_csv(files.gps, spec({"t_unix_s", "lat_deg", "lon_deg", "east_m", "north_m"}, 0.0));
    std::optional<LocalEnu> enu;
    for (std::size_t i = 0; i < g.rows(); ++i) {
      const double lat = g.at(i, 1), lon = g.at(i, 2);
      if (std::abs(lat) > 90.0 || std::abs(lon) > 180.0)
        throw SensorCsvError(files.gps.string() + ": data row " + std::to_string(i + 1) + ": latitude " +
                             std::to_string(lat) + " or longitude " + std::to_string(lon) + " out of range");
      const Geodetic geo = Geodetic::from_degrees(lat, lon, 0.0);
      if (!enu) enu.emplace(geo);
      fusion::GnssFix f;
      f.t = g.at(i, 0);
      f.position = enu->to_enu(geo).head<2>();
      f.fix_quality = 1;  // a single antenna without corrections; the log has no quality column
      logs.gnss.push_back(f);
    }
  }
  return logs;
}

std::vector<fusion::LocalizationState> run_localize(const LocalizeLogs& logs, const LocalizeOptions& options) {
  using fusion::Measurement;
  std::vector<Measurement> all;
  all.reserve(logs.imu.size() + logs.optical.size() + logs.wheels.size() + logs.gnss.size());
  for (const auto& m : logs.imu) all.emplace_back(m);
  for (const auto& m : logs.optical) all.emplace_back(m);
  for (const auto& m : logs.wheels) all.emplace_back(m);
  const Stamp first_fix = logs.gnss.empty() ? 0.0 : logs.gnss.front().t;
  for (const auto& m : logs.gnss) {
    const double rel = m.t - first_fix;
    if (options.gnss_outage && rel >= options.gnss_outage->first && rel <= options.gnss_outage->second) continue;
    all.emplace_back(m);
  }
  // Stable: equal stamps keep the order above (IMU, speed, wheels, GNSS).
  std::stable_sort(all.begin(), all.end(), [](const Measurement& a, const Measurement& b) {
    return fusion::stamp_of(a) < fusion::stamp_of(b);
  });

  auto filter = fusion::make_fusion_filter(options.filter, options.config);
  std::vector<fusion::LocalizationState> out;
  out.reserve(logs.imu.size());
  for (const auto& m : all) {
    filter->add(m);
    if (!std::holds_alternative<fusion::ImuSample>(m)) continue;
    auto s = filter->state();
    if (s.initialised) out.push_back(std::move(s));
  }
  return out;
}

bool write_trajectory_csv(const std::filesystem::path& file, const std::vector<fusion::LocalizationState>& states) {
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(file.c_str(), "w"), &std::fclose);
  if (!f) return false;
  std::fputs("t_unix_s,east_m,north_m,yaw_rad\n", f.get());
  for (const auto& s : states) std::fprintf(f.get(), "%.6f,%.4f,%.4f,%.6f\n", s.stamp, s.pose.x, s.pose.y, s.pose.yaw);
  return std::fflush(f.get()) == 0 && !std::ferror(f.get());
}

}  // namespace fsd
