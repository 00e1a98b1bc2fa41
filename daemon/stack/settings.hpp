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
  // "truth" runs on the virtual car's ground truth (control work, the reference); lidar / lidar_camera run the
  // perception stages on the sensors' bytes.
  std::string perception_source = "truth";
  std::string localization_source = "truth";
  double max_sim_time = 600.0;
  double stats_period = 5.0;  // s between the per-driver rate lines of `fsd run` on the car
};

const ConfigSection<DaemonSettings>& daemon_section();
const ConfigSection<RunSettings>& run_section();

// The schema of the whole configuration file: every library's sections.
std::shared_ptr<const ConfigSchema> config_schema();

}  // namespace fsd
