#pragma once
// The config of a run on the simulator's truth, for tests of what lies past perception and localization (control,
// recording, the service, the CLI): truth perception and truth localization, and the virtual car's LiDAR and camera
// off (nothing reads them then; the run is about ten times faster). The same file a user writes for control work
// (README, "At the desk").
#include <stdexcept>
#include <string>

#include <nlohmann/json.hpp>

namespace fsd::test {

// {"sim": {"enable_camera": false, "enable_lidar": false},
//  "run": {"perception_source": "truth", "localization_source": "truth"}}
// with `patch` merged in as a JSON merge patch (RFC 7386: its keys are added or replace those above, object by
// object; a null removes a key). `patch` must be an object.
inline nlohmann::json truth_sources_json(const nlohmann::json& patch = nlohmann::json::object()) {
  nlohmann::json cfg = {{"sim", {{"enable_camera", false}, {"enable_lidar", false}}},
                        {"run", {{"perception_source", "truth"}, {"localization_source", "truth"}}}};
  if (!patch.is_object()) throw std::invalid_argument("truth_sources: the patch must be a JSON object");
  cfg.merge_patch(patch);
  return cfg;
}

// The same as the text of a config file (`--config`).
inline std::string truth_sources(const nlohmann::json& patch = nlohmann::json::object()) {
  return truth_sources_json(patch).dump();
}

}  // namespace fsd::test
