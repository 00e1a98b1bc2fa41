#include <charconv>
#include <cmath>
#include <iostream>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "daemon/cli/cli.hpp"
#include "daemon/cli/commands.hpp"
#include "daemon/cli/localize_mcap.hpp"
#include "daemon/cli/localize_replay.hpp"
#include "daemon/stack/settings.hpp"
#include "drivers/logs/sensor_csv.hpp"

namespace fsd {

namespace {

struct LocalizeArgs {
  LocalizeLogFiles files;
  std::string out, outage, filter, config, mcap;
};

// --mcap: the recording's NMEA and VCU frames through the fusion filter (daemon/cli/localize_mcap.hpp).
int localize_mcap(const LocalizeArgs& a) {
  if (!a.files.imu.empty() || !a.files.speed.empty() || !a.files.wheels.empty() || !a.files.gps.empty() ||
      !a.outage.empty() || !a.config.empty()) {
    std::cerr << "fsd localize: --mcap takes the sensors and the configuration from the recording: --imu, --speed, "
                 "--wheels, --gps, --gps-outage and --config do not apply\n";
    return kExitBadInput;
  }
  McapLocalization r;
  try {
    r = localize_recording(a.mcap, a.filter);
  } catch (const std::exception& e) {  // McapError, RecordingError, ConfigError: the file is not a usable recording
    std::cerr << "fsd localize: " << a.mcap << ": " << e.what() << "\n";
    return kExitBadInput;
  }
  if (r.states.empty()) {
    std::cerr << "fsd localize: " << a.mcap << ": no pose: " << r.gnss_samples << " GNSS-INS sample(s) in " << r.cycles
              << " cycle(s) gave the filter no position and heading\n";
    return kExitMissionFailed;
  }
  if (!write_trajectory_csv(a.out, r.states)) {
    std::cerr << "fsd localize: cannot write " << a.out << "\n";
    return kExitBadInput;
  }
  std::cout << "fsd localize: " << a.mcap << ": " << r.states.size() << " poses from " << r.gnss_samples
            << " GNSS-INS samples and " << r.vcu_statuses << " VCU statuses over " << r.cycles << " cycles\n";
  return kExitOk;
}

// "A:B" seconds after the first GNSS sample, 0 ≤ A < B.
std::optional<std::pair<double, double>> parse_outage(const std::string& s) {
  const auto colon = s.find(':');
  if (colon == std::string::npos) return std::nullopt;
  double a = 0, b = 0;
  const auto pa = std::from_chars(s.data(), s.data() + colon, a);
  const auto pb = std::from_chars(s.data() + colon + 1, s.data() + s.size(), b);
  if (pa.ec != std::errc() || pa.ptr != s.data() + colon || pb.ec != std::errc() || pb.ptr != s.data() + s.size() ||
      !(a >= 0) || !(b > a) || !std::isfinite(b))
    return std::nullopt;
  return std::make_pair(a, b);
}

int localize(const LocalizeArgs& a) {
  if (!a.mcap.empty()) return localize_mcap(a);
  if (a.files.imu.empty() || a.files.speed.empty()) {
    std::cerr << "fsd localize: --imu and --speed are required (or --mcap FILE)\n";
    return kExitBadInput;
  }
  LocalizeOptions opt;
  const Config cfg = a.config.empty() ? Config(config_schema()) : Config::load(config_schema(), a.config);
  opt.config = fusion::read_fusion_config(cfg);
  opt.filter = a.filter.empty() ? opt.config.common.filter : a.filter;
  if (!a.outage.empty()) {
    opt.gnss_outage = parse_outage(a.outage);
    if (!opt.gnss_outage) {
      std::cerr << "fsd localize: --gps-outage '" << a.outage << "' is not A:B with 0 <= A < B (seconds)\n";
      return kExitBadInput;
    }
    if (a.files.gps.empty()) {
      std::cerr << "fsd localize: --gps-outage needs --gps\n";
      return kExitBadInput;
    }
  }
  LocalizeLogs logs;
  try {
    logs = load_localize_logs(a.files, opt);
  } catch (const SensorCsvError& e) {
    std::cerr << "fsd localize: " << e.what() << "\n";
    return kExitBadInput;
  }
  const auto states = run_localize(logs, opt);
  if (states.empty()) {
    std::cerr << "fsd localize: no pose: "
              << (logs.gnss.empty() ? "without --gps there is no position and heading to start from"
                                    : "the car never drove far enough with GNSS for a heading")
              << "\n";
    return kExitMissionFailed;
  }
  if (!write_trajectory_csv(a.out, states)) {
    std::cerr << "fsd localize: cannot write " << a.out << "\n";
    return kExitBadInput;
  }
  const auto& last = states.back();
  std::cout << "fsd localize: " << opt.filter << ", " << states.size() << " poses, " << last.gnss_counters.accepted
            << " fixes accepted, " << last.gnss_counters.down_weighted << " down-weighted, "
            << last.gnss_counters.rejected << " rejected (" << last.gnss_counters.jumps
            << " jumps); final position sigma " << last.position_sigma() << " m, " << to_string(last.quality)
            << "; gyro bias " << last.gyro_bias << " rad/s, speed scale " << last.speed_scale << "\n";
  return kExitOk;
}

}  // namespace

void add_localize_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand(
      "localize",
      "Fusion of recorded sensor logs (CSV in the format of ../shared/data/amz_2017, or an fsd recording with "
      "--mcap) into a trajectory t_unix_s,east_m,north_m,yaw_rad in the ENU frame of the first GNSS fix (--mcap: "
      "the run's map frame and clock)");
  static LocalizeArgs args;
  cmd->add_option("--imu", args.files.imu, "IMU log: t_unix_s,gyro_x/y/z_rad_s,acc_x/y/z_m_s2");
  cmd->add_option("--speed", args.files.speed, "optical ground speed log: t_unix_s,vx_m_s,vy_m_s");
  cmd->add_option("--mcap", args.mcap, "an fsd recording (fsd run --record): its NMEA and VCU frames instead of CSV")
      ->check(CLI::ExistingFile);
  cmd->add_option("--wheels", args.files.wheels, "wheel log: t_unix_s,fl_rpm,fr_rpm,rl_rpm,rr_rpm (motor rpm)");
  cmd->add_option("--gps", args.files.gps, "GNSS log: t_unix_s,lat_deg,lon_deg,east_m,north_m");
  cmd->add_option("--gps-outage", args.outage, "A:B: GNSS ignored from A to B seconds after the first GNSS sample");
  cmd->add_option("--filter", args.filter, "ekf | complementary (default: localization.fusion.filter)")
      ->check(CLI::IsMember({"ekf", "complementary"}));
  cmd->add_option("--config", args.config, "configuration file whose localization.fusion.* keys apply");
  cmd->add_option("--out", args.out, "trajectory CSV to write")->required();
  cmd->callback([&exit_code] { exit_code = localize(args); });
}

}  // namespace fsd
