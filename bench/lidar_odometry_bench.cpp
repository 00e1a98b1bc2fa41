// LiDAR odometry on one lap of each shared trackdrive, scans rendered by the virtual car's VLP-16 while it drives
// round the centre line at a constant speed (8 m/s by default; a kinematic bicycle steered onto the line): the
// drift against the simulator's true poses and the CPU time per scan (thread CPU clock: one core, so a shared
// machine does not distort it). A plain executable printing a table (not Google Benchmark: one lap is one sample).
// Run from the project root (Release build):
//   build-rel/bench/lidar_odometry_bench [--speed 8] [--measured-motion] [--trace] [--set KEY=VALUE ...] [TRACK.csv ...]
// --trace prints one line per scan: the true and the estimated increment and their difference; --set changes one
// localization.lidar_odometry.* key (a JSON value) for a sweep; --known-start-speed gives the odometry the car's
// speed at the first scan (the drive is a flying start), as wheel speeds would; --measured-motion hands it each
// scan's true mean forward speed and yaw rate, as the daemon hands it the wheel speeds and the GNSS-INS yaw rate.
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/config.hpp"
#include "tests/localization/odometry_lap.hpp"

int main(int argc, char** argv) {
  double speed = 8.0;
  bool trace = false, known_start_speed = false, measured_motion = false;
  std::vector<std::string> tracks;
  auto schema = std::make_shared<fsd::ConfigSchema>();
  fsd::lidar_odometry::describe_lidar_odometry_config(*schema);
  fsd::Config cfg(schema);
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--speed" && i + 1 < argc) {
      speed = std::atof(argv[++i]);
    } else if (a == "--known-start-speed") {
      known_start_speed = true;
    } else if (a == "--measured-motion") {
      measured_motion = true;
    } else if (a == "--trace") {
      trace = true;
    } else if (a == "--set" && i + 1 < argc) {
      const std::string kv = argv[++i];
      const auto eq = kv.find('=');
      try {
        if (eq == std::string::npos) throw fsd::ConfigError("expected KEY=VALUE");
        cfg.set(kv.substr(0, eq), nlohmann::json::parse(kv.substr(eq + 1)), "--set");
      } catch (const std::exception& e) {
        std::fprintf(stderr, "--set %s: %s\n", kv.c_str(), e.what());
        return 2;
      }
    } else if (a.rfind("--", 0) == 0) {
      std::fprintf(stderr,
                   "usage: %s [--speed M_S] [--known-start-speed] [--measured-motion] [--trace] [--set KEY=VALUE ...] "
                   "[TRACK.csv ...]\n",
                   argv[0]);
      return 2;
    } else {
      tracks.push_back(a);
    }
  }
  if (tracks.empty())
    tracks = {"../shared/tracks/epfl_track_1.csv", "../shared/tracks/epfl_track_3.csv",
              "../shared/tracks/epfl_fsds_competition_1.csv"};
  const auto odo_cfg = fsd::lidar_odometry::read_lidar_odometry_config(cfg);
  std::printf(
      "| layout | scans | distance | end-point error | KITTI-style | yaw error | worst scan yaw | degenerate | "
      "ms/scan p50 | p99 |\n|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  for (const auto& t : tracks) {
    const auto r = fsd::test::drive_odometry_lap(t, speed, odo_cfg, trace, known_start_speed, measured_motion);
    std::string name = t.substr(t.find_last_of('/') + 1);
    name = name.substr(0, name.rfind('.'));
    std::printf("| %s | %d | %.1f m | %.2f m (%.2f %%) | %.2f %% | %.2f° | %.2f° | %d | %.2f | %.2f |\n", name.c_str(),
                r.scans, r.distance, r.end_error, r.drift_pct, r.kitti_pct, r.yaw_error_deg, r.max_scan_yaw_error_deg,
                r.degenerate, r.p50_ms(), r.p99_ms());
    std::fflush(stdout);
  }
  return 0;
}
