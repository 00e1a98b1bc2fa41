#include "daemon/stack/settings.hpp"

#include <algorithm>

#include "common/car.hpp"
#include "common/logging.hpp"
#include "common/realtime.hpp"

#include "control/control_config.hpp"
#include "daemon/dds/dds_settings.hpp"
#include "daemon/recording/recorder.hpp"
#include "daemon/service/service_settings.hpp"
#include "daemon/stack/lidar_localization.hpp"
#include "drivers/camera/camera_source.hpp"
#include "drivers/gnss/gnss_config.hpp"
#include "drivers/sim/virtual_car.hpp"
#include "drivers/vcu/vcu_config.hpp"
#include "drivers/vlp16/config.hpp"
#include "localization/cone_map.hpp"
#include "localization/fusion/fusion_config.hpp"
#include "localization/loop_closure/loop_closure_config.hpp"
#include "localization/map_match.hpp"
#include "perception/camera/camera_stage.hpp"
#include "perception/lidar_cone_detector.hpp"
#include "perception/truth_perception.hpp"
#include "web/config.hpp"

namespace fsd {

const ConfigSection<DaemonSettings>& daemon_section() {
  static const auto s = ConfigSection<DaemonSettings>("daemon").string(
      "log_level", &DaemonSettings::log_level, {"trace", "debug", "info", "warn", "error", "critical", "off"},
      "Log level of every component (stderr).")
      .integer("realtime_priority", &DaemonSettings::realtime_priority, 0, 99, "",
               "SCHED_FIFO priority of the control thread (on the virtual car in real time: its loop), so that its "
               "10 ms period holds whatever else the computer runs; the Stack's workers (the scans' processing, "
               "the plans, the lap-2 build, the loop closure) run 10 below it. Needs CAP_SYS_NICE or an "
               "RLIMIT_RTPRIO this high (the service unit's LimitRTPRIO); without, normal scheduling and a warning. "
               "0: normal scheduling.");
  return s;
}

int worker_priority(const DaemonSettings& d) {
  return d.realtime_priority > 0 ? std::max(1, d.realtime_priority - 10) : 0;
}

void make_control_thread_realtime(const DaemonSettings& d) {
  if (d.realtime_priority <= 0) return;
  if (const auto failed = set_realtime(d.realtime_priority))
    logger("run")->warn("the control thread stays at normal scheduling ({}): its period may stretch under load",
                        *failed);
  else
    logger("run")->info("control thread: SCHED_FIFO {}, the workers {}", d.realtime_priority, worker_priority(d));
}

const ConfigSection<RunSettings>& run_section() {
  static const auto s =
      ConfigSection<RunSettings>("run")
          .string("track", &RunSettings::track, {},
                  "Track file (EUFS/FSDS CSV) for the virtual car, relative to the working directory.")
          .string("mission", &RunSettings::mission,
                  {"trackdrive", "autocross", "acceleration", "skidpad", "inspection", "ebs_test"},
                  "Mission selected at start.")
          .integer("laps", &RunSettings::laps, 1, 100, "laps", "Laps of trackdrive (FSAC 2017: 2, FSG: 10).")
          .integer("seed", &RunSettings::seed, 0, 1000000000, "", "Seed of every random process of the virtual car.")
          .string("colours", &RunSettings::colours, {"fsg", "fsac"},
                  "Cone colour convention: fsg = blue left/yellow right, fsac = red left/blue right/yellow timing.")
          .string("perception_source", &RunSettings::perception_source, {"truth", "lidar", "lidar_camera", "dds"},
                  "Where cone detections come from (default: the car's own perception): truth = the virtual car's cones "
                  "within sensor range, for control work and as the reference (on the car, which has no truth: "
                  "lidar_camera when drivers.camera.calibration is set, else lidar); lidar = the "
                  "LiDAR stages on each VLP-16 scan (colour from reflectivity near the car); "
                  "lidar_camera = the LiDAR stages verified and coloured by the camera stage (on the car without "
                  "drivers.camera.calibration: the LiDAR stages alone, with a warning); dds = the frames of a perception process (fsd run --role "
                  "perception) over DDS (split mode, docs/dds.md).")
          .string("localization_source", &RunSettings::localization_source,
                  {"truth", "gnss", "fused", "lidar_odometry"},
                  "Where the pose comes from (default: fused, with the LiDAR odometry in the fusion): truth = the "
                  "virtual car's true pose, for control work and as the reference (on the car: the GNSS-INS pose); "
                  "gnss = the GNSS-INS pose as reported; fused = GNSS-INS and the VCU's wheel speeds through the "
                  "fusion filter (localization.fusion.*), bridging bad or missing fixes; lidar_odometry = without "
                  "satellites: the same filter on the LiDAR odometry, the wheel speeds and the gyro, started at "
                  "localization.start.* and held to the cone map.")
          .number("max_sim_time", &RunSettings::max_sim_time, 1.0, 86400.0, "s",
                  "Headless runs give up after this much simulated time.")
          .number("stats_period", &RunSettings::stats_period, 0.1, 3600.0, "s",
                  "On the car: period of the log line with every driver's rates and error counters.")
          .number("scan_latency", &RunSettings::scan_latency, 0.0, 0.1, "s",
                  "fsd run --sim --headless --workers: a scan's processing (perception, the LiDAR odometry) on the "
                  "processing thread is taken this much simulated time after the scan was handed over, the run "
                  "waiting for it if need be, as long as the processing takes in real time (10-20 ms); the run stays "
                  "repeatable. "
                  "In real time it is taken as soon as it is done.");
  return s;
}

std::shared_ptr<const ConfigSchema> config_schema() {
  auto schema = std::make_shared<ConfigSchema>();
  daemon_section().describe(*schema);
  run_section().describe(*schema);
  describe_car(*schema);
  record_section().describe(*schema);
  truth_perception_section().describe(*schema);
  cone_map_section().describe(*schema);
  map_match_section().describe(*schema);
  fusion::describe_fusion_config(*schema);
  start_pose_section().describe(*schema);
  lidar_odometry::describe_lidar_odometry_config(*schema);
  loop_closure::describe_loop_closure_config(*schema);
  describe_camera_stage(*schema);
  describe_lidar_detector_config(*schema);
  sim::describe_virtual_car_config(*schema);
  describe_control(*schema);
  web::web_section().describe(*schema);
  vcu_section().describe(*schema);
  gnss_section().describe(*schema);
  vlp16_section().describe(*schema);
  camera_driver_section().describe(*schema);
  dds::dds_section().describe(*schema);
  service_section().describe(*schema);
  return schema;
}

}  // namespace fsd
