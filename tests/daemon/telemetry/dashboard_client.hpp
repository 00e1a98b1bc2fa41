#pragma once
// What a dashboard or Prometheus reads from the daemon, for its end-to-end tests: the Foxglove WebSocket protocol
// (subscribe to channels by topic, read their JSON message-data payloads) and the /metrics text.
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "tests/web/test_client.hpp"

namespace fsd::test {

using nlohmann::json;
using web::test::WsClient;

// Subscribes to the given topics (subscription id = index + 1) and waits until the server has taken it.
inline std::map<std::string, std::uint32_t> subscribe(WsClient& c, const std::vector<std::string>& topics) {
  std::map<std::string, std::uint32_t> subs;
  const auto adv = c.next_op("advertise");
  if (!adv) return subs;
  json list = json::array();
  for (const auto& ch : (*adv)["channels"]) {
    for (std::size_t i = 0; i < topics.size(); ++i) {
      if (ch["topic"] == topics[i]) {
        const auto id = static_cast<std::uint32_t>(i + 1);
        list.push_back({{"id", id}, {"channelId", ch["id"]}});
        subs[topics[i]] = id;
      }
    }
  }
  c.send_text(json{{"op", "subscribe"}, {"subscriptions", list}}.dump());
  c.send_text(R"({"op":"getParameters","parameterNames":[],"id":"sync"})");
  c.next_op("parameterValues");
  return subs;
}

inline std::uint32_t u32_le(const std::string& b, std::size_t at) {
  std::uint32_t v = 0;
  for (int i = 3; i >= 0; --i) v = (v << 8) | static_cast<std::uint8_t>(b[at + static_cast<std::size_t>(i)]);
  return v;
}

// The next message-data payload of subscription `sub` (skipping others), parsed.
inline std::optional<json> next_on(WsClient& c, std::uint32_t sub,
                                   std::chrono::milliseconds timeout = std::chrono::seconds(5)) {
  const auto until = std::chrono::steady_clock::now() + timeout;
  while (std::chrono::steady_clock::now() < until) {
    const auto m =
        c.next_binary(std::chrono::duration_cast<std::chrono::milliseconds>(until - std::chrono::steady_clock::now()));
    if (!m) return std::nullopt;
    if (m->size() > 13 && static_cast<std::uint8_t>((*m)[0]) == 0x01 && u32_le(*m, 1) == sub)
      return json::parse(m->substr(13));
  }
  return std::nullopt;
}

// The first message-data payload of each subscription in `subs`, whatever order they arrive in (a message of one
// must not be lost while waiting for another: a short run may send each only once).
inline std::map<std::uint32_t, json> first_on_each(WsClient& c, const std::vector<std::uint32_t>& subs,
                                                   std::chrono::milliseconds timeout = std::chrono::seconds(5)) {
  std::map<std::uint32_t, json> out;
  const auto until = std::chrono::steady_clock::now() + timeout;
  while (out.size() < subs.size() && std::chrono::steady_clock::now() < until) {
    const auto m =
        c.next_binary(std::chrono::duration_cast<std::chrono::milliseconds>(until - std::chrono::steady_clock::now()));
    if (!m) break;
    if (m->size() <= 13 || static_cast<std::uint8_t>((*m)[0]) != 0x01) continue;
    const std::uint32_t sub = u32_le(*m, 1);
    if (std::find(subs.begin(), subs.end(), sub) != subs.end() && !out.count(sub))
      out[sub] = json::parse(m->substr(13));
  }
  return out;
}

// Prometheus text → { "name{labels}": value }.
inline std::map<std::string, double> parse_metrics(const std::string& text) {
  std::map<std::string, double> out;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    const auto sp = line.rfind(' ');
    out[line.substr(0, sp)] = std::stod(line.substr(sp + 1));
  }
  return out;
}

}  // namespace fsd::test
