#pragma once
// The Foxglove WebSocket protocol v1 (subprotocol "foxglove.websocket.v1"), the parts this server speaks:
// serverInfo, status, advertise/unadvertise, binary message data and time, parameterValues; from clients
// subscribe/unsubscribe, getParameters/setParameters and (un)subscribeParameterUpdates. Pure encode/decode,
// no I/O, so every rule of the spec can be tested on bytes.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/time.hpp"

namespace fsd::web::foxglove {

inline constexpr std::string_view kSubprotocol = "foxglove.websocket.v1";
// The name newer Foxglove clients (the Foxglove SDK) offer for the same protocol.
inline constexpr std::string_view kSdkSubprotocol = "foxglove.sdk.v1";

enum class StatusLevel : int { Info = 0, Warning = 1, Error = 2 };

struct ChannelInfo {
  std::uint32_t id = 0;
  std::string topic;
  std::string encoding = "json";
  std::string schema_name;
  std::string schema;  // a JSON schema (text) for encoding "json"
  std::string schema_encoding = "jsonschema";
};

// ---- server → client, JSON (text frames)
std::string server_info(const std::string& name, const std::vector<std::string>& capabilities,
                        const nlohmann::json& metadata, const std::string& session_id);
std::string status(StatusLevel level, const std::string& message);
std::string advertise(const std::vector<ChannelInfo>& channels);
std::string unadvertise(const std::vector<std::uint32_t>& channel_ids);
// `parameters` is an array of {name, value[, type]} objects.
std::string parameter_values(const nlohmann::json& parameters, const std::optional<std::string>& request_id);

// ---- server → client, binary frames (integers little-endian)
inline constexpr std::uint8_t kOpMessageData = 0x01;
inline constexpr std::uint8_t kOpTime = 0x02;
using MessageDataHeader = std::array<std::uint8_t, 13>;  // opcode, subscription id u32, timestamp u64 ns
MessageDataHeader message_data_header(std::uint32_t subscription_id, std::uint64_t timestamp_ns);
std::array<std::uint8_t, 9> time_message(std::uint64_t timestamp_ns);
// Seconds of the run's clock to nanoseconds; negative or non-finite times become 0.
std::uint64_t to_nanoseconds(Stamp t);

// ---- client → server, JSON
struct Subscription {
  std::uint32_t id = 0;
  std::uint32_t channel_id = 0;
};
struct SubscribeOp {
  std::vector<Subscription> subscriptions;
};
struct UnsubscribeOp {
  std::vector<std::uint32_t> subscription_ids;
};
struct GetParametersOp {
  std::vector<std::string> names;  // empty = all
  std::optional<std::string> id;
};
struct ParameterAssignment {
  std::string name;
  nlohmann::json value;  // null when the client asked to unset the parameter
};
struct SetParametersOp {
  std::vector<ParameterAssignment> parameters;
  std::optional<std::string> id;
  std::optional<std::string> token;  // fsd extension: authorises this one request (see docs/dashboard.md)
};
struct SubscribeParameterUpdatesOp {
  std::vector<std::string> names;  // empty = all
};
struct UnsubscribeParameterUpdatesOp {
  std::vector<std::string> names;  // empty = all
};
using ClientOp = std::variant<SubscribeOp, UnsubscribeOp, GetParametersOp, SetParametersOp, SubscribeParameterUpdatesOp,
                              UnsubscribeParameterUpdatesOp>;

struct ParseResult {
  std::optional<ClientOp> op;
  std::string error;  // set when op is empty: what was wrong, for a status message
};
// Parses one text frame from a client. Never throws.
ParseResult parse_client_message(std::string_view text);

}  // namespace fsd::web::foxglove
