#pragma once
// A foxglove.SceneUpdate channel sent as changes (docs/dashboard.md, "Scene deltas"): the scene is kept by entity
// id, each update carries only the entities whose content changed and `deletions` for the ids that went away, and
// the whole current scene is kept beside it for a client that subscribes later (the hub latches it). The cone map
// and the paths are mostly the same from one update to the next; sending them whole cost most of a client's Wi-Fi.
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/time.hpp"

namespace fsd::web {

class SceneDelta {
 public:
  struct Update {
    std::string delta;  // SceneUpdate: the changed and new entities, deletions of the gone ones
    std::string full;   // SceneUpdate: a deletion of all (type 1), then every current entity
  };
  // `entities`: the whole scene now, foxglove.SceneEntity objects with unique "id"s. nullopt when nothing changed
  // (an entity's timestamp alone is no change: the client already draws it).
  std::optional<Update> update(Stamp t, const std::vector<nlohmann::json>& entities);
  std::size_t size() const { return sent_.size(); }

 private:
  struct Sent {
    std::string content;  // the entity without its timestamp: what decides whether it changed
    std::string text;     // the entity as last sent, for the full scene
  };
  std::map<std::string, Sent> sent_;
};

// {"deletions": [], "entities": [...]}: a whole scene.
std::string scene_update_json(const std::vector<nlohmann::json>& entities);

}  // namespace fsd::web
