#include <iostream>
#include <string>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "daemon/cli/cli.hpp"
#include "daemon/cli/cloud_detect.hpp"
#include "daemon/cli/commands.hpp"
#include "daemon/stack/settings.hpp"
#include "drivers/cloud/csv_cloud.hpp"
#include "drivers/vlp16/laser_table.hpp"
#include "drivers/vlp16/pcap_reader.hpp"

namespace fsd {

namespace {

struct DetectArgs {
  std::string cloud, config;
  bool json = false;
};

int detect(const DetectArgs& a) {
  LoadedCloud cloud;
  try {
    cloud = load_cloud(a.cloud);
  } catch (const CloudError& e) {
    std::cerr << "fsd detect: " << e.what() << "\n";
    return kExitBadInput;
  } catch (const PcapError& e) {
    std::cerr << "fsd detect: " << e.what() << "\n";
    return kExitBadInput;
  } catch (const LaserTableError& e) {
    std::cerr << "fsd detect: " << e.what() << "\n";
    return kExitBadInput;
  }
  // A bad configuration throws ConfigError, reported by run_cli with exit 2.
  const Config cfg = a.config.empty() ? Config(config_schema()) : Config::load(config_schema(), a.config);
  LidarConeDetector detector(detect_frame_config(read_lidar_detector_config(cfg), cloud), Pose3::Identity());
  const LidarDetection d = detector.detect(cloud.scan);
  if (a.json) {
    std::cout << detection_json(d).dump() << "\n";
  } else {
    std::cout << detection_table(a.cloud, cloud, d);
  }
  if (!d.ground.valid) {
    std::cerr << "fsd detect: no ground plane found in " << a.cloud << "\n";
    return kExitMissionFailed;
  }
  return kExitOk;
}

}  // namespace

void add_detect_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand(
      "detect",
      "LiDAR cone detection on one cloud in its own frame (x forward, y left, z up at the sensor): a CSV "
      "x,y,z[,intensity] (header optional) or a VLP-16 pcap (its first full revolution)");
  static DetectArgs args;
  cmd->add_option("--cloud", args.cloud, "CSV or pcap file")->required();
  cmd->add_flag("--json", args.json,
                "print {\"cones\": [{x,y,z,colour,confidence,points}], \"ground\": {a,b,h}} (z = a*x + b*y + h)");
  cmd->add_option("--config", args.config, "configuration file whose perception.lidar.* keys apply");
  cmd->callback([&exit_code] { exit_code = detect(args); });
}

}  // namespace fsd
