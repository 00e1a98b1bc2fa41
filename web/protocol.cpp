#include "web/protocol.hpp"

#include <cmath>
#include <limits>

#include "web/json_text.hpp"

namespace fsd::web::foxglove {

using nlohmann::json;

namespace {

template <class T>
void put_le(std::uint8_t* out, T v) {
  for (std::size_t i = 0; i < sizeof(T); ++i) out[i] = static_cast<std::uint8_t>(v >> (8 * i));
}

// Reads an unsigned 32-bit id; error text when it is not one.
std::optional<std::uint32_t> as_u32(const json& v) {
  if (!v.is_number_integer()) return std::nullopt;
  if (v.is_number_unsigned()) {
    const auto u = v.get<std::uint64_t>();
    if (u > std::numeric_limits<std::uint32_t>::max()) return std::nullopt;
    return static_cast<std::uint32_t>(u);
  }
  const auto s = v.get<std::int64_t>();
  if (s < 0 || s > std::numeric_limits<std::uint32_t>::max()) return std::nullopt;
  return static_cast<std::uint32_t>(s);
}

std::optional<std::vector<std::string>> string_array(const json& msg, const char* field, bool required,
                                                     std::string& error) {
  const auto it = msg.find(field);
  if (it == msg.end() || it->is_null()) {
    if (required) error = std::string("missing '") + field + "'";
    return required ? std::nullopt : std::optional<std::vector<std::string>>(std::vector<std::string>{});
  }
  if (!it->is_array()) {
    error = std::string("'") + field + "' must be an array of strings";
    return std::nullopt;
  }
  std::vector<std::string> out;
  for (const auto& e : *it) {
    if (!e.is_string()) {
      error = std::string("'") + field + "' must be an array of strings";
      return std::nullopt;
    }
    out.push_back(e.get<std::string>());
  }
  return out;
}

std::optional<std::string> optional_string(const json& msg, const char* field, std::string& error) {
  const auto it = msg.find(field);
  if (it == msg.end() || it->is_null()) return std::nullopt;
  if (!it->is_string()) {
    error = std::string("'") + field + "' must be a string";
    return std::nullopt;
  }
  return it->get<std::string>();
}

ParseResult fail(std::string why) { return {std::nullopt, std::move(why)}; }

ParseResult parse_subscribe(const json& msg) {
  const auto it = msg.find("subscriptions");
  if (it == msg.end() || !it->is_array()) return fail("subscribe: 'subscriptions' must be an array");
  SubscribeOp op;
  for (const auto& s : *it) {
    if (!s.is_object()) return fail("subscribe: each subscription must be an object {id, channelId}");
    const auto id = s.contains("id") ? as_u32(s["id"]) : std::nullopt;
    const auto ch = s.contains("channelId") ? as_u32(s["channelId"]) : std::nullopt;
    if (!id || !ch) return fail("subscribe: 'id' and 'channelId' must be unsigned 32-bit integers");
    op.subscriptions.push_back({*id, *ch});
  }
  return {op, {}};
}

ParseResult parse_unsubscribe(const json& msg) {
  const auto it = msg.find("subscriptionIds");
  if (it == msg.end() || !it->is_array()) return fail("unsubscribe: 'subscriptionIds' must be an array");
  UnsubscribeOp op;
  for (const auto& s : *it) {
    const auto id = as_u32(s);
    if (!id) return fail("unsubscribe: subscription ids must be unsigned 32-bit integers");
    op.subscription_ids.push_back(*id);
  }
  return {op, {}};
}

ParseResult parse_set_parameters(const json& msg) {
  const auto it = msg.find("parameters");
  if (it == msg.end() || !it->is_array()) return fail("setParameters: 'parameters' must be an array");
  SetParametersOp op;
  std::string error;
  op.id = optional_string(msg, "id", error);
  op.token = optional_string(msg, "token", error);
  if (!error.empty()) return fail("setParameters: " + error);
  for (const auto& p : *it) {
    if (!p.is_object() || !p.contains("name") || !p["name"].is_string())
      return fail("setParameters: each parameter must be an object with a string 'name'");
    const auto v = p.find("value");
    op.parameters.push_back({p["name"].get<std::string>(), v == p.end() ? json() : *v});
  }
  return {op, {}};
}

}  // namespace

std::string server_info(const std::string& name, const std::vector<std::string>& capabilities, const json& metadata,
                        const std::string& session_id) {
  return json{{"op", "serverInfo"},
              {"name", name},
              {"capabilities", capabilities},
              {"metadata", metadata},
              {"sessionId", session_id}}
      .dump();
}

std::string status(StatusLevel level, const std::string& message) {
  // Replace invalid UTF-8 (a message may quote client input) rather than throw.
  return json{{"op", "status"}, {"level", static_cast<int>(level)}, {"message", message}}.dump(
      -1, ' ', false, json::error_handler_t::replace);
}

std::string advertise(const std::vector<ChannelInfo>& channels) {
  json arr = json::array();
  for (const auto& c : channels)
    arr.push_back({{"id", c.id},
                   {"topic", c.topic},
                   {"encoding", c.encoding},
                   {"schemaName", c.schema_name},
                   {"schema", c.schema},
                   {"schemaEncoding", c.schema_encoding}});
  return json{{"op", "advertise"}, {"channels", arr}}.dump();
}

std::string unadvertise(const std::vector<std::uint32_t>& channel_ids) {
  return json{{"op", "unadvertise"}, {"channelIds", channel_ids}}.dump();
}

std::string parameter_values(const json& parameters, const std::optional<std::string>& request_id) {
  json msg{{"op", "parameterValues"}, {"parameters", parameters}};
  if (request_id) msg["id"] = *request_id;
  return msg.dump(-1, ' ', false, json::error_handler_t::replace);
}

MessageDataHeader message_data_header(std::uint32_t subscription_id, std::uint64_t timestamp_ns) {
  MessageDataHeader h{};
  h[0] = kOpMessageData;
  put_le(h.data() + 1, subscription_id);
  put_le(h.data() + 5, timestamp_ns);
  return h;
}

std::array<std::uint8_t, 9> time_message(std::uint64_t timestamp_ns) {
  std::array<std::uint8_t, 9> m{};
  m[0] = kOpTime;
  put_le(m.data() + 1, timestamp_ns);
  return m;
}

std::uint64_t to_nanoseconds(Stamp t) {
  if (!std::isfinite(t) || t <= 0.0) return 0;
  const double ns = std::round(t * 1e9);
  if (ns >= 1.8e19) return std::numeric_limits<std::uint64_t>::max();
  return static_cast<std::uint64_t>(ns);
}

ParseResult parse_client_message(std::string_view text) {
  const auto parsed = parse_json_text(text);
  if (parsed.value.is_discarded()) return fail(parsed.error);
  const json& msg = parsed.value;
  if (!msg.is_object()) return fail("a message must be a JSON object");
  const auto op_it = msg.find("op");
  if (op_it == msg.end() || !op_it->is_string()) return fail("a message needs a string field 'op'");
  const auto op = op_it->get<std::string>();
  std::string error;

  if (op == "subscribe") return parse_subscribe(msg);
  if (op == "unsubscribe") return parse_unsubscribe(msg);
  if (op == "setParameters") return parse_set_parameters(msg);
  if (op == "getParameters") {
    GetParametersOp g;
    auto names = string_array(msg, "parameterNames", false, error);
    g.id = optional_string(msg, "id", error);
    if (!error.empty()) return fail("getParameters: " + error);
    g.names = std::move(*names);
    return {g, {}};
  }
  if (op == "subscribeParameterUpdates" || op == "unsubscribeParameterUpdates") {
    auto names = string_array(msg, "parameterNames", false, error);
    if (!error.empty()) return fail(op + ": " + error);
    if (op == "subscribeParameterUpdates") return {SubscribeParameterUpdatesOp{std::move(*names)}, {}};
    return {UnsubscribeParameterUpdatesOp{std::move(*names)}, {}};
  }
  // Valid ops of the protocol whose capability this server does not declare.
  if (op == "advertise" || op == "unadvertise")
    return fail("op '" + op + "' needs capability clientPublish, not offered");
  if (op == "subscribeConnectionGraph" || op == "unsubscribeConnectionGraph")
    return fail("op '" + op + "' needs capability connectionGraph, not offered");
  if (op == "fetchAsset") return fail("op 'fetchAsset' needs capability assets, not offered");
  return fail("unknown op '" + op.substr(0, 64) + "'");
}

}  // namespace fsd::web::foxglove
