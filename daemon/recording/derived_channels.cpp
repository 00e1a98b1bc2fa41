#include "daemon/recording/derived_channels.hpp"

#include <nlohmann/json.hpp>

#include "web/scene_delta.hpp"

namespace fsd {

namespace {
const char* const kParamChangeSchema = R"({"type": "object", "title": "fsd.ParamChange",
 "description": "A live parameter change the Stack accepted, with who made it.",
 "properties": {"t": {"type": "number", "description": "run clock, s"},
  "key": {"type": "string"}, "old": {"type": "number"}, "new": {"type": "number"},
  "who": {"type": "string", "description": "the client: web address and token state, cli, ..."}}})";

}  // namespace

std::vector<web::ChannelSpec> derived_channel_specs() {
  std::vector<web::ChannelSpec> out;
  // The table's rows with a recording rate; never the simulator's truth (its raw frames are recorded).
  for (auto& spec : channel_specs([](const TelemetryChannel& c) { return c.record_hz && !c.truth; }))
    out.push_back(std::move(spec));
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

DerivedChannels::DerivedChannels(web::CarShape car)
    : use_{car, true}, pacer_(telemetry_channels(), [](const TelemetryChannel& c) {
        return c.truth ? std::optional<double>() : c.record_hz;
      }) {}

std::vector<DerivedMessage> DerivedChannels::messages(const TelemetrySnapshot& s) {
  const auto& rows = telemetry_channels();
  std::vector<DerivedMessage> out;
  for (const std::size_t i : pacer_.due(s, s.t)) {
    auto p = rows[i].build(s, use_);
    if (!p) continue;
    out.push_back({rows[i].spec.topic, s.t, p->entities ? web::scene_update_json(*p->entities) : std::move(p->json)});
  }
  return out;
}

}  // namespace fsd
