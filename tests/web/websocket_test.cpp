// The Foxglove WebSocket protocol end to end: a real Beast client against the server on 127.0.0.1.
#include <gtest/gtest.h>

#include <cstring>
#include <map>

#include "tests/web/test_client.hpp"
#include "web/channels.hpp"
#include "web/hub.hpp"

namespace fsd::web::test {
namespace {

using nlohmann::json;

std::uint32_t u32_le(const std::string& b, std::size_t at) {
  std::uint32_t v = 0;
  for (int i = 3; i >= 0; --i) v = (v << 8) | static_cast<std::uint8_t>(b[at + i]);
  return v;
}
std::uint64_t u64_le(const std::string& b, std::size_t at) {
  std::uint64_t v = 0;
  for (int i = 7; i >= 0; --i) v = (v << 8) | static_cast<std::uint8_t>(b[at + i]);
  return v;
}

// Subscribes and waits until the server has processed it (a getParameters reply comes after it, in order).
void subscribe(WsClient& c, std::uint32_t sub, ChannelId ch) {
  ASSERT_TRUE(c.send_text(json{{"op", "subscribe"}, {"subscriptions", {{{"id", sub}, {"channelId", ch}}}}}.dump()));
  ASSERT_TRUE(c.send_text(R"({"op":"getParameters","parameterNames":[],"id":"sync"})"));
  ASSERT_TRUE(c.next_op("parameterValues"));
}

TEST(WebSocket, HandshakeSelectsTheFoxgloveSubprotocolAndGreets) {
  TestServer s;
  const auto ch = s.server->add_channel("/vehicle/state", "fsd.VehicleState", R"({"type":"object"})");
  WsClient c(s.port());
  ASSERT_TRUE(c.handshake_ok());
  EXPECT_EQ(c.accepted_subprotocol(), "foxglove.websocket.v1");

  const auto info = c.next();
  ASSERT_TRUE(info && !info->binary);
  const auto j = info->json();
  EXPECT_EQ(j["op"], "serverInfo");
  const auto caps = j["capabilities"].get<std::vector<std::string>>();
  EXPECT_NE(std::find(caps.begin(), caps.end(), "parameters"), caps.end());
  EXPECT_NE(std::find(caps.begin(), caps.end(), "parametersSubscribe"), caps.end());

  const auto adv = c.next_op("advertise");
  ASSERT_TRUE(adv);
  ASSERT_EQ((*adv)["channels"].size(), 1u);
  const auto& channel = (*adv)["channels"][0];
  EXPECT_EQ(channel["id"], ch);
  EXPECT_EQ(channel["topic"], "/vehicle/state");
  EXPECT_EQ(channel["encoding"], "json");
  EXPECT_EQ(channel["schemaName"], "fsd.VehicleState");
  EXPECT_EQ(json::parse(channel["schema"].get<std::string>())["type"], "object");
}

TEST(WebSocket, RefusesClientsWithoutTheSubprotocol) {
  TestServer s;
  WsClient::Options none;
  none.subprotocols = {};
  WsClient a(s.port(), none);
  EXPECT_FALSE(a.handshake_ok());
  EXPECT_EQ(a.status(), 400u);

  WsClient::Options other;
  other.subprotocols = {"chat", "foxglove.websocket.v2"};
  WsClient b(s.port(), other);
  EXPECT_FALSE(b.handshake_ok());
  EXPECT_EQ(b.status(), 400u);

  WsClient::Options among;
  among.subprotocols = {"chat", "foxglove.websocket.v1"};
  WsClient c(s.port(), among);
  EXPECT_TRUE(c.handshake_ok());
}

TEST(WebSocket, TheSdkNameOfTheSubprotocolIsAcceptedAndEchoed) {
  TestServer s;
  s.server->add_channel("/vehicle/state", "fsd.VehicleState", R"({"type":"object"})");
  WsClient::Options sdk;
  sdk.subprotocols = {"foxglove.sdk.v1"};
  WsClient a(s.port(), sdk);
  ASSERT_TRUE(a.handshake_ok());
  EXPECT_EQ(a.accepted_subprotocol(), "foxglove.sdk.v1");  // a client checks the server took what it offered
  EXPECT_TRUE(a.next_op("advertise"));                     // and it is the same protocol

  WsClient::Options both;  // offered both: the classic name
  both.subprotocols = {"foxglove.sdk.v1", "foxglove.websocket.v1"};
  WsClient b(s.port(), both);
  ASSERT_TRUE(b.handshake_ok());
  EXPECT_EQ(b.accepted_subprotocol(), "foxglove.websocket.v1");
}

TEST(WebSocket, ChannelsAddedLaterAreAdvertised) {
  TestServer s;
  WsClient c(s.port());
  ASSERT_TRUE(c.next_op("advertise"));
  const auto ch = s.server->add_channel("/late", "fsd.Late", "{}");
  const auto adv = c.next_op("advertise");
  ASSERT_TRUE(adv);
  EXPECT_EQ((*adv)["channels"][0]["id"], ch);
  EXPECT_EQ((*adv)["channels"][0]["topic"], "/late");
}

TEST(WebSocket, SubscribedChannelArrivesAsBinaryMessageData) {
  TestServer s;
  const auto ch = s.server->add_channel("/a", "A", "{}");
  WsClient c(s.port());
  subscribe(c, 42, ch);
  s.server->publish(ch, 12.5, R"({"v":1})");
  const auto m = c.next_binary();
  ASSERT_TRUE(m);
  ASSERT_EQ(m->size(), 1u + 4u + 8u + 7u);
  EXPECT_EQ(static_cast<std::uint8_t>((*m)[0]), 0x01);
  EXPECT_EQ(u32_le(*m, 1), 42u);
  EXPECT_EQ(u64_le(*m, 5), 12'500'000'000ull);
  EXPECT_EQ(m->substr(13), R"({"v":1})");
}

TEST(WebSocket, UnsubscribeStopsData) {
  TestServer s;
  const auto a = s.server->add_channel("/a", "A", "{}");
  const auto b = s.server->add_channel("/b", "B", "{}");
  WsClient c(s.port());
  subscribe(c, 1, a);
  subscribe(c, 2, b);
  s.server->publish(a, 1.0, "\"a1\"");
  auto m = c.next_binary();
  ASSERT_TRUE(m);
  EXPECT_EQ(m->substr(13), "\"a1\"");

  ASSERT_TRUE(c.send_text(R"({"op":"unsubscribe","subscriptionIds":[1]})"));
  ASSERT_TRUE(c.send_text(R"({"op":"getParameters","parameterNames":[],"id":"sync"})"));
  ASSERT_TRUE(c.next_op("parameterValues"));
  s.server->publish(a, 2.0, "\"a2\"");
  s.server->publish(b, 2.0, "\"b2\"");  // a marker: whatever comes first after the unsubscribe
  m = c.next_binary();
  ASSERT_TRUE(m);
  EXPECT_EQ(u32_le(*m, 1), 2u);
  EXPECT_EQ(m->substr(13), "\"b2\"");
}

TEST(WebSocket, LatchedChannelSendsItsLastMessageToNewSubscribers) {
  TestServer s;
  const auto ch = s.server->add_channel("/map", "M", "{}", ChannelOptions{true});
  const auto marker = s.server->add_channel("/marker", "K", "{}");
  WsClient first(s.port());
  subscribe(first, 1, marker);
  s.server->publish(ch, 3.0, "\"old\"");
  s.server->publish(ch, 4.0, "\"latest\"");
  s.server->publish(marker, 5.0, "\"m\"");
  ASSERT_TRUE(first.next_binary());  // messages are taken in order: both map messages are in by now

  WsClient late(s.port());
  ASSERT_TRUE(late.send_text(json{{"op", "subscribe"}, {"subscriptions", {{{"id", 7}, {"channelId", ch}}}}}.dump()));
  const auto m = late.next_binary();
  ASSERT_TRUE(m);
  EXPECT_EQ(u32_le(*m, 1), 7u);
  EXPECT_EQ(u64_le(*m, 5), 4'000'000'000ull);
  EXPECT_EQ(m->substr(13), "\"latest\"");
  EXPECT_FALSE(late.next_binary(300ms));  // only the last one
}

TEST(WebSocket, BacklogChannelSendsItsRecentMessagesToNewSubscribersInOrder) {
  TestServer s;
  const auto log = s.server->add_channel("/log", "L", "{}", ChannelOptions{false, 3});
  const auto marker = s.server->add_channel("/marker", "K", "{}");
  WsClient first(s.port());
  subscribe(first, 1, marker);
  for (int i = 1; i <= 5; ++i) s.server->publish(log, i, "\"line " + std::to_string(i) + "\"");
  s.server->publish(marker, 6.0, "\"m\"");
  ASSERT_TRUE(first.next_binary());  // taken in order: the five lines are in by now

  WsClient late(s.port());  // opened after the lines: gets the last three, oldest first, and no more
  ASSERT_TRUE(late.send_text(json{{"op", "subscribe"}, {"subscriptions", {{{"id", 4}, {"channelId", log}}}}}.dump()));
  for (int i = 3; i <= 5; ++i) {
    const auto m = late.next_binary();
    ASSERT_TRUE(m) << "line " << i;
    EXPECT_EQ(u32_le(*m, 1), 4u);
    EXPECT_EQ(m->substr(13), "\"line " + std::to_string(i) + "\"");
  }
  EXPECT_FALSE(late.next_binary(300ms));
  s.server->publish(log, 7.0, "\"live\"");  // and then the live ones
  const auto m = late.next_binary();
  ASSERT_TRUE(m);
  EXPECT_EQ(m->substr(13), "\"live\"");
}

TEST(WebSocket, ChannelsAreAdvertisedUnderTheIdsAddChannelsGave) {
  TestServer s;
  const auto ids = add_channels(*s.server, {channel_spec(topics::kConeMap, Schema::SceneUpdate, "cones"),
                                            channel_spec(topics::kVehicleState, Schema::VehicleState, "state"),
                                            channel_spec(topics::kLog, Schema::Log, "log", {.backlog = 5})});
  WsClient client(s.port());
  const auto adv = client.next_op("advertise");
  ASSERT_TRUE(adv);
  std::map<std::string, ChannelId> advertised;
  for (const auto& ch : (*adv)["channels"]) {
    advertised[ch["topic"].get<std::string>()] = ch["id"].get<ChannelId>();
    EXPECT_EQ(json::parse(ch["schema"].get<std::string>())["title"], ch["schemaName"]);
  }
  EXPECT_EQ(advertised, ids.by_topic);
  EXPECT_EQ(ids.at(topics::kLog), advertised.at("/log"));
  EXPECT_THROW(ids.at("/nope"), std::out_of_range);
}

TEST(WebSocket, SubscribeErrorsAreReported) {
  TestServer s;
  const auto ch = s.server->add_channel("/a", "A", "{}");
  WsClient c(s.port());
  ASSERT_TRUE(c.send_text(json{{"op", "subscribe"}, {"subscriptions", {{{"id", 1}, {"channelId", 99}}}}}.dump()));
  auto st = c.next_op("status");
  ASSERT_TRUE(st);
  EXPECT_EQ((*st)["level"], 2);
  EXPECT_NE((*st)["message"].get<std::string>().find("unknown channel 99"), std::string::npos);
  subscribe(c, 1, ch);
  ASSERT_TRUE(c.send_text(json{{"op", "subscribe"}, {"subscriptions", {{{"id", 1}, {"channelId", ch}}}}}.dump()));
  st = c.next_op("status");
  ASSERT_TRUE(st);
  EXPECT_NE((*st)["message"].get<std::string>().find("in use"), std::string::npos);
}

TEST(WebSocket, GetParametersListsTheRegistry) {
  TestServer s;
  WsClient c(s.port());
  ASSERT_TRUE(c.send_text(R"({"op":"getParameters","parameterNames":["control.target_speed","nope"],"id":"r1"})"));
  const auto warn = c.next_op("status");
  ASSERT_TRUE(warn);
  EXPECT_NE((*warn)["message"].get<std::string>().find("nope"), std::string::npos);
  auto pv = c.next_op("parameterValues");
  ASSERT_TRUE(pv);
  EXPECT_EQ((*pv)["id"], "r1");
  ASSERT_EQ((*pv)["parameters"].size(), 1u);
  EXPECT_EQ((*pv)["parameters"][0]["name"], "control.target_speed");
  EXPECT_DOUBLE_EQ((*pv)["parameters"][0]["value"].get<double>(), 5.0);
  EXPECT_EQ((*pv)["parameters"][0]["type"], "float64");

  ASSERT_TRUE(c.send_text(R"({"op":"getParameters","parameterNames":[]})"));
  pv = c.next_op("parameterValues");
  ASSERT_TRUE(pv);
  EXPECT_FALSE(pv->contains("id"));
  std::map<std::string, json> by_name;
  for (const auto& p : (*pv)["parameters"]) by_name[p["name"]] = p["value"];
  ASSERT_EQ(by_name.size(), 3u);
  EXPECT_EQ(by_name["control.lookahead_points"], 10);
  EXPECT_EQ(by_name["control.use_gnss"], true);
}

TEST(WebSocket, SetParametersWithoutTokenIsRefusedAndChangesNothing) {
  TestServer s;
  WsClient c(s.port());
  ASSERT_TRUE(
      c.send_text(R"({"op":"setParameters","parameters":[{"name":"control.target_speed","value":9.0}],"id":"s1"})"));
  const auto st = c.next_op("status");
  ASSERT_TRUE(st);
  EXPECT_EQ((*st)["level"], 2);
  EXPECT_NE((*st)["message"].get<std::string>().find("token"), std::string::npos);
  const auto pv = c.next_op("parameterValues");  // the unchanged value, so a client's editor reverts
  ASSERT_TRUE(pv);
  EXPECT_EQ((*pv)["id"], "s1");
  EXPECT_DOUBLE_EQ((*pv)["parameters"][0]["value"].get<double>(), 5.0);
  EXPECT_DOUBLE_EQ(*s.params.get("control.target_speed"), 5.0);

  // A wrong token in the message is refused the same way.
  ASSERT_TRUE(c.send_text(
      R"({"op":"setParameters","parameters":[{"name":"control.target_speed","value":9.0}],"token":"guess"})"));
  ASSERT_TRUE(c.next_op("status"));
  EXPECT_DOUBLE_EQ(*s.params.get("control.target_speed"), 5.0);
  EXPECT_TRUE(s.params.history().empty());
}

TEST(WebSocket, SetParametersWithTokenInTheMessageChangesTheRegistry) {
  TestServer s;
  WsClient c(s.port());
  ASSERT_TRUE(c.send_text(json{
      {"op", "setParameters"},
      {"parameters",
       {{{"name", "control.target_speed"}, {"value", 7.5}}, {{"name", "control.use_gnss"}, {"value", false}}}},
      {"id", "s2"},
      {"token", kToken}}.dump()));
  const auto pv = c.next_op("parameterValues");
  ASSERT_TRUE(pv);
  EXPECT_EQ((*pv)["id"], "s2");
  EXPECT_DOUBLE_EQ(*s.params.get("control.target_speed"), 7.5);
  EXPECT_DOUBLE_EQ(*s.params.get("control.use_gnss"), 0.0);
  const auto h = s.params.history();
  ASSERT_EQ(h.size(), 2u);
  EXPECT_NE(h[0].who.find("web 127.0.0.1:"), std::string::npos);  // attributed to the client's address
}

TEST(WebSocket, TokenInTheUrlAuthorisesTheConnection) {
  TestServer s;
  WsClient::Options o;
  o.target = std::string("/?token=") + kToken;
  WsClient c(s.port(), o);
  ASSERT_TRUE(c.handshake_ok());
  ASSERT_TRUE(
      c.send_text(R"({"op":"setParameters","parameters":[{"name":"control.lookahead_points","value":12}],"id":"x"})"));
  ASSERT_TRUE(c.next_op("parameterValues"));
  EXPECT_DOUBLE_EQ(*s.params.get("control.lookahead_points"), 12.0);
}

TEST(WebSocket, WrongTokenInTheUrlLeavesTheConnectionReadOnly) {
  TestServer s;
  WsClient::Options o;
  o.target = "/?token=wrong";
  WsClient c(s.port(), o);
  ASSERT_TRUE(c.handshake_ok());
  const auto st = c.next_op("status");
  ASSERT_TRUE(st);
  EXPECT_EQ((*st)["level"], 1);
  ASSERT_TRUE(c.send_text(R"({"op":"setParameters","parameters":[{"name":"control.lookahead_points","value":12}]})"));
  ASSERT_TRUE(c.next_op("status"));
  EXPECT_DOUBLE_EQ(*s.params.get("control.lookahead_points"), 10.0);
}

TEST(WebSocket, OutOfBoundsValuesAreRefusedAllOrNothing) {
  TestServer s;
  WsClient c(s.port());
  ASSERT_TRUE(c.send_text(json{
      {"op", "setParameters"},
      {"parameters",
       {{{"name", "control.lookahead_points"}, {"value", 20}}, {{"name", "control.target_speed"}, {"value", 25.0}}}},
      {"token", kToken}}.dump()));
  const auto st = c.next_op("status");
  ASSERT_TRUE(st);
  EXPECT_NE((*st)["message"].get<std::string>().find("control.target_speed"), std::string::npos);
  EXPECT_DOUBLE_EQ(*s.params.get("control.target_speed"), 5.0);
  EXPECT_DOUBLE_EQ(*s.params.get("control.lookahead_points"), 10.0);  // the valid one was not applied either
}

TEST(WebSocket, TuningDisabledWithoutAConfiguredToken) {
  auto cfg = TestServer::base_config();
  cfg.token = "";
  TestServer s(cfg);
  WsClient c(s.port());
  ASSERT_TRUE(
      c.send_text(R"({"op":"setParameters","parameters":[{"name":"control.target_speed","value":6}],"token":""})"));
  const auto st = c.next_op("status");
  ASSERT_TRUE(st);
  EXPECT_NE((*st)["message"].get<std::string>().find("disabled"), std::string::npos);
  EXPECT_DOUBLE_EQ(*s.params.get("control.target_speed"), 5.0);
}

TEST(WebSocket, ParameterSubscribersHearOfChanges) {
  TestServer s;
  WsClient watcher(s.port());
  ASSERT_TRUE(watcher.send_text(R"({"op":"subscribeParameterUpdates","parameterNames":["control.target_speed"]})"));
  ASSERT_TRUE(watcher.send_text(R"({"op":"getParameters","parameterNames":[],"id":"sync"})"));
  ASSERT_TRUE(watcher.next_op("parameterValues"));
  ASSERT_TRUE(s.params.set("control.lookahead_points", 3, "test").ok);  // not subscribed: no message
  ASSERT_TRUE(s.params.set("control.target_speed", 8.25, "test").ok);
  const auto pv = watcher.next_op("parameterValues");
  ASSERT_TRUE(pv);
  ASSERT_EQ((*pv)["parameters"].size(), 1u);
  EXPECT_EQ((*pv)["parameters"][0]["name"], "control.target_speed");
  EXPECT_DOUBLE_EQ((*pv)["parameters"][0]["value"].get<double>(), 8.25);
}

TEST(WebSocket, MalformedJsonAndUnknownOpsGetErrorStatusAndTheConnectionLives) {
  TestServer s;
  WsClient c(s.port());
  ASSERT_TRUE(c.send_text("{\"op\": \"subscribe\", "));
  auto st = c.next_op("status");
  ASSERT_TRUE(st);
  EXPECT_EQ((*st)["level"], 2);
  EXPECT_NE((*st)["message"].get<std::string>().find("malformed JSON"), std::string::npos);

  ASSERT_TRUE(c.send_text(R"({"op":"launchRocket"})"));
  st = c.next_op("status");
  ASSERT_TRUE(st);
  EXPECT_NE((*st)["message"].get<std::string>().find("unknown op 'launchRocket'"), std::string::npos);

  ASSERT_TRUE(c.send_text(R"({"op":"advertise","channels":[]})"));  // client publishing is not offered
  st = c.next_op("status");
  ASSERT_TRUE(st);
  EXPECT_NE((*st)["message"].get<std::string>().find("clientPublish"), std::string::npos);

  ASSERT_TRUE(c.send_binary(std::string("\x01\x00\x00\x00\x00", 5)));
  st = c.next_op("status");
  ASSERT_TRUE(st);
  EXPECT_EQ((*st)["level"], 2);

  ASSERT_TRUE(c.send_text(R"({"op":"getParameters","parameterNames":[],"id":"alive"})"));
  EXPECT_TRUE(c.next_op("parameterValues"));
}

TEST(WebSocket, OversizeMessagesAreRefusedAndAbuseCloses) {
  auto cfg = TestServer::base_config();
  cfg.max_frame_bytes = 2048;
  TestServer s(cfg);
  WsClient c(s.port());
  ASSERT_TRUE(c.send_text(R"({"op":"getParameters","parameterNames":[],"id":")" + std::string(5000, 'x') + "\"}"));
  const auto st = c.next_op("status");
  ASSERT_TRUE(st);
  EXPECT_NE((*st)["message"].get<std::string>().find("larger than 2048 bytes"), std::string::npos);
  ASSERT_TRUE(c.send_text(R"({"op":"getParameters","parameterNames":[],"id":"alive"})"));
  ASSERT_TRUE(c.next_op("parameterValues"));

  // A client that keeps sending garbage is disconnected with "policy violation".
  for (int i = 0; i < 15; ++i) c.send_text("not json");
  const auto code = c.wait_closed();
  ASSERT_TRUE(code);
  EXPECT_EQ(*code, 1008);
}

TEST(WebSocket, MessageRateIsLimited) {
  auto cfg = TestServer::base_config();
  cfg.max_incoming_msgs_per_s = 5;
  TestServer s(cfg);
  WsClient c(s.port());
  for (int i = 0; i < 12; ++i)
    ASSERT_TRUE(c.send_text(R"({"op":"getParameters","parameterNames":["control.use_gnss"]})"));
  int replies = 0;
  bool rate_status = false;
  while (auto m = c.next(500ms)) {
    const auto j = m->json();
    if (j["op"] == "parameterValues") ++replies;
    if (j["op"] == "status" && j["message"].get<std::string>().find("messages per second") != std::string::npos)
      rate_status = true;
  }
  EXPECT_TRUE(rate_status);
  EXPECT_GE(replies, 5);
  EXPECT_LT(replies, 12);
}

TEST(WebSocket, TooManyClientsAreRefusedUntilOneLeaves) {
  auto cfg = TestServer::base_config();
  cfg.max_clients = 2;
  TestServer s(cfg);
  auto a = std::make_unique<WsClient>(s.port());
  WsClient b(s.port());
  ASSERT_TRUE(a->handshake_ok());
  ASSERT_TRUE(b.handshake_ok());
  WsClient refused(s.port());
  EXPECT_FALSE(refused.handshake_ok());
  EXPECT_EQ(refused.status(), 503u);
  a.reset();
  for (int i = 0; i < 300 && s.server->client_count() > 1; ++i) std::this_thread::sleep_for(10ms);
  WsClient later(s.port());
  EXPECT_TRUE(later.handshake_ok());
}

TEST(WebSocket, OriginOfAnotherSiteIsRefused) {
  TestServer s;
  WsClient::Options evil;
  evil.origin = "http://evil.example";
  WsClient a(s.port(), evil);
  EXPECT_FALSE(a.handshake_ok());
  EXPECT_EQ(a.status(), 403u);
  WsClient::Options same;
  same.origin = "http://127.0.0.1:" + std::to_string(s.port());
  WsClient b(s.port(), same);
  EXPECT_TRUE(b.handshake_ok());
}

TEST(WebSocket, AllowedOriginsListLetsOtherSitesIn) {
  auto cfg = TestServer::base_config();
  cfg.allowed_origins = "https://app.foxglove.dev, http://pit.local:5173";
  TestServer s(cfg);
  WsClient::Options studio;
  studio.origin = "https://app.foxglove.dev";
  EXPECT_TRUE(WsClient(s.port(), studio).handshake_ok());
  WsClient::Options other;
  other.origin = "http://pit.local:8080";
  EXPECT_FALSE(WsClient(s.port(), other).handshake_ok());
}

// A client that never reads: publish() keeps returning, that client's queue drops its oldest messages, and a
// client that reads gets every message.
TEST(WebSocket, StalledClientLosesOldestTelemetryWhileOthersGetEverything) {
  auto cfg = TestServer::base_config();
  cfg.client_send_queue = 32;
  TestServer s(cfg);
  const auto ch = s.server->add_channel("/bulk", "B", "{}");
  WsClient::Options stalled_opts;
  stalled_opts.read = false;
  stalled_opts.receive_buffer = 4096;
  WsClient stalled(s.port(), stalled_opts);
  WsClient good(s.port());
  ASSERT_TRUE(stalled.handshake_ok());
  ASSERT_TRUE(stalled.send_text(json{{"op", "subscribe"}, {"subscriptions", {{{"id", 5}, {"channelId", ch}}}}}.dump()));
  subscribe(good, 6, ch);
  // Publish in bursts smaller than the queue and let the good client drain each burst: it must lose nothing.
  const std::string pad(8 * 1024, 'p');
  constexpr int kMessages = 1200, kBurst = 16;
  std::vector<int> got;
  for (int i = 0; i < kMessages; ++i) {
    s.server->publish(ch, i * 0.01, "{\"seq\":" + std::to_string(i) + ",\"pad\":\"" + pad + "\"}");
    if ((i + 1) % kBurst == 0 || i + 1 == kMessages) {
      while (static_cast<int>(got.size()) < i + 1) {
        const auto m = good.next_binary(5000ms);
        ASSERT_TRUE(m) << "good client stalled at " << got.size();
        got.push_back(json::parse(m->substr(13))["seq"].get<int>());
      }
    }
  }
  for (int i = 0; i < kMessages; ++i) ASSERT_EQ(got[i], i);

  const auto metrics = s.server->metrics().render();
  const std::string sample = "\nfsd_web_messages_dropped_total ";
  const auto pos = metrics.find(sample);
  ASSERT_NE(pos, std::string::npos);
  const auto dropped = std::stoull(metrics.substr(pos + sample.size()));
  EXPECT_GT(dropped, 0u);

  // Now the stalled client reads: whatever sat in the socket buffers first, then the newest messages; the
  // last one it gets is the last one published (the oldest were dropped, not the newest).
  stalled.start_reading();
  std::vector<int> late;
  while (auto m = stalled.next_binary(1000ms)) late.push_back(json::parse(m->substr(13))["seq"].get<int>());
  ASSERT_FALSE(late.empty());
  EXPECT_LT(late.size(), static_cast<std::size_t>(kMessages));
  EXPECT_EQ(late.back(), kMessages - 1);
  EXPECT_TRUE(std::is_sorted(late.begin(), late.end()));
  // The tail is contiguous: the queue held the newest messages (its 32 slots are shared with the few time
  // messages of the last moments, so look at the last 16).
  const std::size_t tail = std::min<std::size_t>(late.size(), 16);
  for (std::size_t i = late.size() - tail + 1; i < late.size(); ++i) EXPECT_EQ(late[i], late[i - 1] + 1);
}

TEST(WebSocket, TimeMessagesCarryTheServerClock) {
  TestServer s;
  WsClient::Options o;
  o.keep_time = true;
  const double before = s.clock.now();
  WsClient c(s.port(), o);
  const auto m = c.next_binary();
  const double after = s.clock.now();
  ASSERT_TRUE(m);
  ASSERT_EQ(m->size(), 9u);
  EXPECT_EQ(static_cast<std::uint8_t>((*m)[0]), 0x02);
  const double t = static_cast<double>(u64_le(*m, 1)) * 1e-9;
  EXPECT_GE(t, before - 1e-6);
  EXPECT_LE(t, after + 1e-6);
}

TEST(WebSocket, IdleClientsThatDoNotAnswerPingsAreClosed) {
  auto cfg = TestServer::base_config();
  cfg.idle_timeout_s = 1;
  TestServer s(cfg);
  WsClient::Options mute;
  mute.read = false;  // never reads, so never answers the server's pings
  WsClient silent(s.port(), mute);
  WsClient alive(s.port());  // reads, and Beast answers pings by itself
  ASSERT_TRUE(silent.handshake_ok());
  ASSERT_TRUE(alive.next_op("advertise"));
  for (int i = 0; i < 500 && s.server->client_count() > 1; ++i) std::this_thread::sleep_for(10ms);
  EXPECT_EQ(s.server->client_count(), 1u);
  std::this_thread::sleep_for(1500ms);  // well past the idle timeout: the live client is still there
  EXPECT_EQ(s.server->client_count(), 1u);
  ASSERT_TRUE(alive.send_text(R"({"op":"getParameters","parameterNames":[],"id":"still"})"));
  EXPECT_TRUE(alive.next_op("parameterValues"));
}

TEST(WebSocket, TwoIoThreadsServeTheSameProtocol) {
  auto cfg = TestServer::base_config();
  cfg.io_threads = 2;
  TestServer s(cfg);
  const auto ch = s.server->add_channel("/a", "A", "{}");
  WsClient a(s.port()), b(s.port());
  subscribe(a, 1, ch);
  subscribe(b, 2, ch);
  for (int i = 0; i < 100; ++i) s.server->publish(ch, i, std::to_string(i));
  for (auto* c : {&a, &b})
    for (int i = 0; i < 100; ++i) {
      const auto m = c->next_binary();
      ASSERT_TRUE(m);
      EXPECT_EQ(m->substr(13), std::to_string(i));
    }
}

TEST(WebSocket, StopClosesClientsWithGoingAway) {
  auto s = std::make_unique<TestServer>();
  WsClient c(s->port());
  ASSERT_TRUE(c.next_op("advertise"));
  s->server->stop();
  const auto code = c.wait_closed();
  ASSERT_TRUE(code);
  EXPECT_EQ(*code, 1001);
}

}  // namespace
}  // namespace fsd::web::test
