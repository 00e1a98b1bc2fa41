#pragma once
// Settings of the daemon itself (the wiring), declared as configuration sections.
#include <memory>
#include <string>

#include "common/config.hpp"

namespace fsd {

struct DaemonSettings {
  std::string log_level = "info";
  int realtime_priority = 50;  // SCHED_FIFO of the control thread (0: normal scheduling)
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
  double scan_latency = 0.02;  // s: a paced run takes a scan's processing so long after its hand-over
};

const ConfigSection<DaemonSettings>& daemon_section();
// The SCHED_FIFO priority of the Stack's workers: 10 below the control thread's, at least 1 (0: normal scheduling).
int worker_priority(const DaemonSettings& d);
// The calling thread (the control thread) under SCHED_FIFO at daemon.realtime_priority, said in the log either way.
void make_control_thread_realtime(const DaemonSettings& d);
const ConfigSection<RunSettings>& run_section();

// The schema of the whole configuration file: every library's sections.
std::shared_ptr<const ConfigSchema> config_schema();

}  // namespace fsd
