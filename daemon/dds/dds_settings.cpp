#include "daemon/dds/dds_settings.hpp"

#include <arpa/inet.h>

#include <algorithm>
#include <sstream>
#include <stdexcept>

namespace fsd::dds {

namespace {

std::vector<std::string> split_list(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream in(s);
  std::string item;
  while (std::getline(in, item, ',')) {
    item.erase(0, item.find_first_not_of(" \t"));
    item.erase(item.find_last_not_of(" \t") + 1);
    if (!item.empty()) out.push_back(item);
  }
  return out;
}

}  // namespace

const ConfigSection<DdsSettings>& dds_section() {
  static const auto s =
      ConfigSection<DdsSettings>("dds")
          .boolean("enabled", &DdsSettings::enabled,
                   "Publish the stack's topics over DDS (Fast DDS, named and typed as ROS 2 does: docs/dds.md). Off: "
                   "no DDS participant at all.")
          .integer("domain", &DdsSettings::domain, 0, 232, "",
                   "DDS domain id (ROS_DOMAIN_ID of the ROS 2 tools that should see the topics).")
          .string("topics", &DdsSettings::topics, {},
                  "Topics published: all, or a comma-separated list of cloud, detections, map, odom, command, "
                  "status, laps, faults (docs/dds.md).")
          .string("initial_peers", &DdsSettings::initial_peers, {},
                  "Comma-separated IPv4 addresses of the other participants' hosts, discovered by unicast where "
                  "multicast does not reach (e.g. 127.0.0.1, or the perception computer's address).")
          .boolean("multicast", &DdsSettings::multicast,
                   "Discover participants by multicast as well; off: only the initial peers (and this host).")
          .number("max_detection_age", &DdsSettings::max_detection_age, 0.01, 5.0, "s",
                  "run.perception_source = dds: remote detections older than this on arrival are dropped as late "
                  "(counted); no detections for control.supervisor.lidar_timeout is the silent-LiDAR fault.")
          .string("sim_lidar_address", &DdsSettings::sim_lidar_address, {},
                  "fsd run --sim with run.perception_source = dds: the address the virtual car's VLP-16 packets "
                  "go to (the perception process's drivers.vlp16.address).")
          .integer("sim_lidar_port", &DdsSettings::sim_lidar_port, 1, 65535, "",
                   "fsd run --sim with run.perception_source = dds: the UDP port of those packets (the perception "
                   "process's drivers.vlp16.data_port).")
          .boolean("sim_camera", &DdsSettings::sim_camera,
                   "fsd run --sim with run.perception_source = dds: the virtual camera's JPEG frames go out on "
                   "/fsd/camera/image/compressed for the perception process.");
  return s;
}

std::set<std::string> parse_topics(const std::string& topics) {
  const auto names = split_list(topics);
  if (names.size() == 1 && names[0] == "all") return {kTopicNames.begin(), kTopicNames.end()};
  std::set<std::string> out;
  for (const auto& n : names) {
    if (std::find(kTopicNames.begin(), kTopicNames.end(), n) == kTopicNames.end())
      throw std::invalid_argument("dds.topics: unknown topic '" + n +
                                  "' (all, or cloud, detections, map, odom, command, status, laps, faults)");
    out.insert(n);
  }
  return out;
}

std::vector<std::string> parse_peers(const std::string& peers) {
  auto out = split_list(peers);
  for (const auto& p : out) {
    in_addr a{};
    if (inet_pton(AF_INET, p.c_str(), &a) != 1)
      throw std::invalid_argument("dds.initial_peers: '" + p + "' is not an IPv4 address");
  }
  return out;
}

}  // namespace fsd::dds
