#include "daemon/derived_channels.hpp"

#include <nlohmann/json.hpp>

namespace fsd {

namespace {
const char* const kParamChangeSchema = R"({"type": "object", "title": "fsd.ParamChange",
 "description": "A live parameter change the Stack accepted, with who made it.",
 "properties": {"t": {"type": "number", "description": "run clock, s"},
  "key": {"type": "string"}, "old": {"type": "number"}, "new": {"type": "number"},
  "who": {"type": "string", "description": "the client: web address and token state, cli, ..."}}})";

// The dashboard's channels a recording carries: everything but the camera picture, whose bytes the raw JPEG
// frames already hold. The point cloud only as perception split it (ground and obstacles), thinned: the raw
// VLP-16 packets hold every point.
bool recorded(const std::string& topic) {
  return topic != web::topics::kCameraImage && topic != web::topics::kCameraDetections;
}
}  // namespace

std::vector<web::ChannelSpec> derived_channel_specs() {
  std::vector<web::ChannelSpec> out;
  for (auto& spec : web::standard_channels())
    if (recorded(spec.topic)) out.push_back(std::move(spec));
  web::ChannelSpec params;
  params.topic = kParamChangesTopic;
  params.schema_name = "fsd.ParamChange";
  params.schema = kParamChangeSchema;
  out.push_back(std::move(params));
  return out;
}

std::string param_change_json(const ParamChange& c) {
  return nlohmann::json{{"t", c.t}, {"key", c.key}, {"old", c.old_value}, {"new", c.new_value}, {"who", c.who}}.dump();
}

std::vector<DerivedMessage> DerivedChannels::messages(const TelemetrySnapshot& s) {
  namespace topics = web::topics;
  std::vector<DerivedMessage> out;
  out.push_back({topics::kVehicleState, s.t, web::vehicle_state_json(s.state, s.target_speed)});
  out.push_back({topics::kCar, s.t, web::car_scene(s.t, s.state.pose, car_)});
  const auto due = [&s](Stamp last, double hz) { return s.t - last >= 1.0 / hz - 1e-9; };
  if (s.detections && s.detections != detections_ && due(detections_at_, rates_.detections_hz)) {
    detections_ = s.detections;
    detections_at_ = s.t;
    out.push_back({topics::kDetections, s.t,
                   web::detections_scene(s.t, *s.detections, s.detections_pose.value_or(s.state.pose))});
  }
  if (due(map_at_, rates_.map_hz) && ((s.cone_map && s.cone_map != cone_map_) || (s.paths && s.paths != paths_))) {
    map_at_ = s.t;
    if (s.cone_map && s.cone_map != cone_map_) {
      cone_map_ = s.cone_map;
      out.push_back({topics::kConeMap, s.t, web::cone_map_scene(s.t, *s.cone_map)});
    }
    if (s.paths && s.paths != paths_) {
      paths_ = s.paths;
      out.push_back({topics::kPaths, s.t, web::paths_scene(s.t, *s.paths)});
    }
  }
  if (s.cloud && s.cloud != cloud_ && due(cloud_at_, rates_.cloud_hz)) {
    cloud_ = s.cloud;
    cloud_at_ = s.t;
    web::CloudOptions thin;
    thin.max_points = rates_.cloud_points;
    out.push_back(
        {topics::kPointCloud, s.t, web::point_cloud(s.t, s.cloud_pose, s.cloud->ground, s.cloud->obstacles, thin)});
  }
  if (due(status_at_, rates_.status_hz) || s.as.as_state != as_state_) {
    status_at_ = s.t;
    as_state_ = s.as.as_state;
    out.push_back({topics::kAsStatus, s.t, web::as_status_json(s.t, s.as)});
  }
  const std::string newest = s.faults.empty() ? "" : s.faults.back().source + s.faults.back().what;
  if (s.faults.size() != faults_ || newest != last_fault_) {
    faults_ = s.faults.size();
    last_fault_ = newest;
    out.push_back({topics::kFaults, s.t, web::faults_json(s.t, s.faults)});
  }
  return out;
}

}  // namespace fsd
