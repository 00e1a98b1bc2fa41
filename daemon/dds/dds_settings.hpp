#pragma once
// The DDS bridge's configuration (`dds.*`, docs/dds.md): whether it runs, its domain, the topics it publishes,
// the peers it discovers without multicast, and split mode's own keys.
#include <set>
#include <string>
#include <vector>

#include "common/config.hpp"

namespace fsd::dds {

struct DdsSettings {
  bool enabled = false;
  int domain = 0;
  std::string topics = "all";      // comma-separated names of kTopicNames, or "all"
  std::string initial_peers = "";  // comma-separated IPv4 addresses discovered by unicast (e.g. 127.0.0.1)
  bool multicast = true;           // discovery by multicast as well (off: the initial peers only)
  double max_detection_age = 0.3;  // s: remote detections older than this when they arrive are dropped as late
  // `fsd run --sim` with run.perception_source = dds: where the virtual car's VLP-16 packets go (the perception
  // process's drivers.vlp16.data_port) and whether its camera frames go out on /fsd/camera/image/compressed.
  std::string sim_lidar_address = "127.0.0.1";
  int sim_lidar_port = 2368;
  bool sim_camera = true;
};
const ConfigSection<DdsSettings>& dds_section();

// The topics `dds.topics` may name (docs/dds.md has their ROS 2 names and types).
inline const std::vector<std::string> kTopicNames = {"cloud",   "detections", "map",  "odom",
                                                     "command", "status",     "laps", "faults"};

// The names in `dds.topics`; throws std::invalid_argument naming the key and the unknown name.
std::set<std::string> parse_topics(const std::string& topics);
// The addresses in `dds.initial_peers`; throws std::invalid_argument naming the key and the bad address.
std::vector<std::string> parse_peers(const std::string& peers);

}  // namespace fsd::dds
