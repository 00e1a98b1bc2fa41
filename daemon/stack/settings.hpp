#pragma once
// Settings of the daemon itself (the wiring), declared as configuration sections.
#include <memory>
#include <string>

#include "common/config.hpp"

namespace fsd {

struct DaemonSettings {
  std::string log_level = "info";
};

struct RunSettings {
  std::string track = "../shared/tracks/epfl_track_1.csv";
  std::string mission = "trackdrive";
  int laps = 2;
  int seed = 1;
  std::string colours = "fsg";
  // The real loop by default: the perception stages on the sensors' bytes, the pose from GNSS-INS fused with the
  // wheel speeds and the LiDAR odometry. "truth" (the virtual car's ground truth) stays for control work and as the
  // reference (--vs-truth).
  std::string perception_source = "lidar_camera";
  std::string localization_source = "fused";
  double max_sim_time = 600.0;
  double stats_period = 5.0;  // s between the per-driver rate lines of `fsd run` on the car
};

const ConfigSection<DaemonSettings>& daemon_section();
const ConfigSection<RunSettings>& run_section();

// The schema of the whole configuration file: every library's sections.
std::shared_ptr<const ConfigSchema> config_schema();

}  // namespace fsd
