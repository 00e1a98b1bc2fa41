#include "web/scene_delta.hpp"

#include <set>

namespace fsd::web {

using nlohmann::json;

namespace {
constexpr auto kReplace = json::error_handler_t::replace;

json stamp_of(Stamp t) {
  if (!(t > 0)) t = 0;
  const auto sec = static_cast<std::int64_t>(t);
  auto nsec = static_cast<std::int64_t>((t - static_cast<double>(sec)) * 1e9 + 0.5);
  if (nsec > 999999999) nsec = 999999999;
  return {{"sec", sec}, {"nsec", nsec}};
}

std::string join_scene(const std::string& deletions, const std::vector<const std::string*>& entities) {
  std::string out = "{\"deletions\":" + deletions + ",\"entities\":[";
  for (std::size_t i = 0; i < entities.size(); ++i) {
    if (i) out += ',';
    out += *entities[i];
  }
  return out + "]}";
}
}  // namespace

std::optional<SceneDelta::Update> SceneDelta::update(Stamp t, const std::vector<json>& entities) {
  std::vector<std::string> changed;
  std::set<std::string> present;
  for (const auto& e : entities) {
    const std::string id = e.value("id", "");
    if (!present.insert(id).second) continue;  // a duplicate id would replace its twin on the client
    json bare = e;
    bare.erase("timestamp");
    std::string content = bare.dump(-1, ' ', false, kReplace);
    auto it = sent_.find(id);
    if (it != sent_.end() && it->second.content == content) continue;
    std::string text = e.dump(-1, ' ', false, kReplace);
    changed.push_back(text);
    sent_[id] = Sent{std::move(content), std::move(text)};
  }
  json deletions = json::array();
  for (auto it = sent_.begin(); it != sent_.end();) {
    if (present.count(it->first)) {
      ++it;
      continue;
    }
    deletions.push_back({{"timestamp", stamp_of(t)}, {"type", 0}, {"id", it->first}});  // 0: MATCHING_ID
    it = sent_.erase(it);
  }
  if (changed.empty() && deletions.empty()) return std::nullopt;
  Update u;
  std::vector<const std::string*> list;
  for (const auto& c : changed) list.push_back(&c);
  u.delta = join_scene(deletions.dump(), list);
  list.clear();
  for (const auto& [id, s] : sent_) list.push_back(&s.text);
  // Whole: everything the client has of this topic goes first (a resync after a lost change must not leave a
  // deleted entity standing); Foxglove applies a SceneUpdate's deletions before its entities.
  u.full = join_scene(json::array({{{"timestamp", stamp_of(t)}, {"type", 1}, {"id", ""}}}).dump(), list);
  return u;
}

std::string scene_update_json(const std::vector<json>& entities) {
  return json{{"deletions", json::array()}, {"entities", entities}}.dump(-1, ' ', false, kReplace);
}

}  // namespace fsd::web
