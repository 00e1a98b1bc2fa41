// Foxglove WebSocket v1 messages as bytes and JSON, against the spec's field names and layouts.
#include <gtest/gtest.h>

#include "web/protocol.hpp"

namespace fsd::web::foxglove {
namespace {

using nlohmann::json;

TEST(Protocol, MessageDataHeaderIsLittleEndian) {
  const auto h = message_data_header(0x04030201u, 0x0807060504030201ull);
  const std::array<std::uint8_t, 13> expected{0x01, 0x01, 0x02, 0x03, 0x04, 0x01, 0x02,
                                              0x03, 0x04, 0x05, 0x06, 0x07, 0x08};
  EXPECT_EQ(h, expected);
  const auto t = time_message(1'000'000'001ull);  // 0x3B9ACA01
  const std::array<std::uint8_t, 9> te{0x02, 0x01, 0xCA, 0x9A, 0x3B, 0, 0, 0, 0};
  EXPECT_EQ(t, te);
}

TEST(Protocol, SecondsToNanoseconds) {
  EXPECT_EQ(to_nanoseconds(1.5), 1'500'000'000ull);
  EXPECT_EQ(to_nanoseconds(0.000000001), 1ull);
  EXPECT_EQ(to_nanoseconds(-3.0), 0ull);
  EXPECT_EQ(to_nanoseconds(std::nan("")), 0ull);
}

TEST(Protocol, ServerMessagesHaveTheSpecFields) {
  auto j = json::parse(server_info("fsd", {"parameters"}, json{{"k", "v"}}, "123"));
  EXPECT_EQ(j["op"], "serverInfo");
  EXPECT_EQ(j["capabilities"], json::array({"parameters"}));
  EXPECT_EQ(j["sessionId"], "123");
  EXPECT_EQ(j["metadata"]["k"], "v");
  j = json::parse(status(StatusLevel::Warning, "careful"));
  EXPECT_EQ(j, (json{{"op", "status"}, {"level", 1}, {"message", "careful"}}));
  ChannelInfo c;
  c.id = 3;
  c.topic = "/t";
  c.schema_name = "S";
  c.schema = "{}";
  j = json::parse(advertise({c}));
  EXPECT_EQ(j["channels"][0], (json{{"id", 3},
                                    {"topic", "/t"},
                                    {"encoding", "json"},
                                    {"schemaName", "S"},
                                    {"schema", "{}"},
                                    {"schemaEncoding", "jsonschema"}}));
  j = json::parse(parameter_values(json::array({{{"name", "a"}, {"value", 1}}}), std::string("req")));
  EXPECT_EQ(j["op"], "parameterValues");
  EXPECT_EQ(j["id"], "req");
  EXPECT_FALSE(json::parse(parameter_values(json::array(), std::nullopt)).contains("id"));
  // Invalid UTF-8 from a client quoted in a status must not throw.
  EXPECT_NO_THROW(status(StatusLevel::Error, std::string("bad \xff byte")));
}

TEST(Protocol, ParsesSubscribeAndUnsubscribe) {
  auto r =
      parse_client_message(R"({"op":"subscribe","subscriptions":[{"id":0,"channelId":3},{"id":1,"channelId":5}]})");
  ASSERT_TRUE(r.op);
  const auto& sub = std::get<SubscribeOp>(*r.op);
  ASSERT_EQ(sub.subscriptions.size(), 2u);
  EXPECT_EQ(sub.subscriptions[1].id, 1u);
  EXPECT_EQ(sub.subscriptions[1].channel_id, 5u);
  r = parse_client_message(R"({"op":"unsubscribe","subscriptionIds":[0,1]})");
  ASSERT_TRUE(r.op);
  EXPECT_EQ(std::get<UnsubscribeOp>(*r.op).subscription_ids, (std::vector<std::uint32_t>{0, 1}));
}

TEST(Protocol, ParsesParameterOps) {
  auto r = parse_client_message(R"({"op":"getParameters","parameterNames":["a","b"],"id":"x"})");
  ASSERT_TRUE(r.op);
  EXPECT_EQ(std::get<GetParametersOp>(*r.op).names, (std::vector<std::string>{"a", "b"}));
  EXPECT_EQ(std::get<GetParametersOp>(*r.op).id, "x");
  r = parse_client_message(R"({"op":"getParameters"})");
  ASSERT_TRUE(r.op);
  EXPECT_TRUE(std::get<GetParametersOp>(*r.op).names.empty());
  r = parse_client_message(
      R"({"op":"setParameters","parameters":[{"name":"a","value":1.5},{"name":"b"}],"id":"y","token":"t"})");
  ASSERT_TRUE(r.op);
  const auto& set = std::get<SetParametersOp>(*r.op);
  ASSERT_EQ(set.parameters.size(), 2u);
  EXPECT_EQ(set.parameters[0].value, 1.5);
  EXPECT_TRUE(set.parameters[1].value.is_null());
  EXPECT_EQ(set.token, "t");
  r = parse_client_message(R"({"op":"subscribeParameterUpdates","parameterNames":["a"]})");
  ASSERT_TRUE(r.op);
  EXPECT_EQ(std::get<SubscribeParameterUpdatesOp>(*r.op).names, std::vector<std::string>{"a"});
  r = parse_client_message(R"({"op":"unsubscribeParameterUpdates","parameterNames":[]})");
  ASSERT_TRUE(r.op);
  EXPECT_TRUE(std::get<UnsubscribeParameterUpdatesOp>(*r.op).names.empty());
}

TEST(Protocol, RejectsMalformedMessagesWithAReason) {
  const std::pair<const char*, const char*> cases[] = {
      {"{", "malformed JSON"},
      {R"({"op":"setParameters","parameters":[{"name":"a","value":1e999}]})", "'1e999' is out of range"},
      {"[1,2]", "JSON object"},
      {R"({"opx":"subscribe"})", "'op'"},
      {R"({"op":7})", "'op'"},
      {R"({"op":"subscribe"})", "'subscriptions'"},
      {R"({"op":"subscribe","subscriptions":[{"id":-1,"channelId":1}]})", "unsigned 32-bit"},
      {R"({"op":"subscribe","subscriptions":[{"id":4294967296,"channelId":1}]})", "unsigned 32-bit"},
      {R"({"op":"subscribe","subscriptions":[{"id":1.5,"channelId":1}]})", "unsigned 32-bit"},
      {R"({"op":"unsubscribe","subscriptionIds":["a"]})", "unsigned 32-bit"},
      {R"({"op":"getParameters","parameterNames":[1]})", "array of strings"},
      {R"({"op":"setParameters","parameters":[{"value":1}]})", "string 'name'"},
      {R"({"op":"setParameters","parameters":[],"token":5})", "'token'"},
      {R"({"op":"fetchAsset","uri":"x","requestId":1})", "assets"},
      {R"({"op":"subscribeConnectionGraph"})", "connectionGraph"},
      {R"({"op":"selfDestruct"})", "unknown op 'selfDestruct'"},
  };
  for (const auto& [text, why] : cases) {
    const auto r = parse_client_message(text);
    EXPECT_FALSE(r.op) << text;
    EXPECT_NE(r.error.find(why), std::string::npos) << text << " → " << r.error;
  }
  // Deep nesting is parsed without blowing the stack and refused as not an op.
  const std::string deep = std::string(20000, '[') + std::string(20000, ']');
  EXPECT_FALSE(parse_client_message(deep).op);
}

}  // namespace
}  // namespace fsd::web::foxglove
