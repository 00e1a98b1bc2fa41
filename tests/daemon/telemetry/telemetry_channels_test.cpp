// The channel table and its pacing: one row per channel with a valid schema, the recording's and the dashboard's
// channel sets, and the rates a row gets when polled as the telemetry thread polls it (every 10 ms) — counted
// against the wall of numbers a 25 Hz channel must give, not the code's own arithmetic.
#include <gtest/gtest.h>

#include <map>
#include <set>

#include <nlohmann/json.hpp>

#include "daemon/recording/derived_channels.hpp"
#include "daemon/telemetry/telemetry_channels.hpp"

namespace fsd {
namespace {

using nlohmann::json;

const TelemetryChannel& row(const std::string& topic) {
  for (const auto& r : telemetry_channels())
    if (r.spec.topic == topic) return r;
  throw std::out_of_range(topic);
}

TEST(ChannelTable, EveryChannelOnceWithItsSchemaAndABuilderUnlessFedElsewhere) {
  std::set<std::string> topics;
  for (const auto& r : telemetry_channels()) {
    EXPECT_TRUE(topics.insert(r.spec.topic).second) << r.spec.topic;
    const auto schema = json::parse(r.spec.schema);
    EXPECT_EQ(schema["title"], r.spec.schema_name) << r.spec.topic;
    EXPECT_EQ(schema["type"], "object");
    EXPECT_EQ(r.build == nullptr, r.spec.topic == "/log") << r.spec.topic;  // the log has its sink
    EXPECT_EQ(r.truth, r.spec.topic.starts_with("/truth/")) << r.spec.topic;
  }
  // /camera/detections is not in it: nothing hands the camera's boxes to the telemetry yet.
  EXPECT_EQ(topics, (std::set<std::string>{"/map/cones", "/perception/cones", "/vehicle/car", "/planning/paths",
                                           "/lidar/points", "/camera/image", "/vehicle/state", "/as/status", "/faults",
                                           "/log", "/localization/estimate", "/localization/loop_closures",
                                           "/truth/cones", "/truth/car", "/truth/vehicle_state", "/truth/path",
                                           "/truth/localization_error"}));
  // The scene the dashboard sends as changes, kept whole for late subscribers.
  EXPECT_TRUE(row("/map/cones").spec.options.delta && row("/map/cones").spec.options.latched);
  EXPECT_TRUE(row("/planning/paths").spec.options.delta);
  EXPECT_EQ(json::parse(row("/lidar/points").spec.schema)["properties"]["data"]["contentEncoding"], "base64");
  EXPECT_EQ(row("/log").spec.options.backlog, 100u);
}

TEST(ChannelTable, ARecordingCarriesTheStacksChannelsButNotTheCameraOrTheTruth) {
  std::set<std::string> recorded;
  for (const auto& s : derived_channel_specs()) recorded.insert(s.topic);
  EXPECT_EQ(recorded, (std::set<std::string>{"/map/cones", "/perception/cones", "/vehicle/car", "/planning/paths",
                                             "/lidar/points", "/vehicle/state", "/as/status", "/faults", "/log",
                                             "/params/changes"}));
}

// Snapshots every 40 ms (every 4th cycle at 100 Hz) polled every 10 ms for 10 s: how many messages each row gives.
std::map<std::string, int> count_live(const std::function<void(TelemetrySnapshot&, int)>& vary) {
  ChannelPacer pacer(telemetry_channels(), [](const TelemetryChannel& c) { return c.live_hz; });
  std::map<std::string, int> n;
  auto snap = std::make_shared<TelemetrySnapshot>();
  for (int tick = 0; tick < 1000; ++tick) {
    const bool fresh = tick % 4 == 0;
    if (fresh) {
      snap = std::make_shared<TelemetrySnapshot>(*snap);
      snap->t = tick * 0.01;
      vary(*snap, tick);
    }
    for (const auto i : pacer.due(*snap, tick * 0.01 + 1e-4 * (tick % 3), fresh))  // a little poll jitter
      ++n[telemetry_channels()[i].spec.topic];
  }
  return n;
}

TEST(ChannelPacer, LiveRatesAreTheTablesWhenPolledInStepsAndNewDataOnly) {
  const auto n = count_live([](TelemetrySnapshot& s, int tick) {
    s.cone_map = std::make_shared<const std::vector<Cone>>();  // a new map each snapshot (as the Stack's)
    if (tick == 0) s.camera_jpeg = std::make_shared<const std::vector<std::uint8_t>>(3, 0);  // one picture only
    s.as.as_state = tick < 504 ? AsState::Ready : AsState::Driving;  // 5.04 s: between two 5 Hz messages
  });
  EXPECT_NEAR(n.at("/vehicle/state"), 250, 2);  // 25 Hz over 10 s: every snapshot (it was 20 Hz before)
  EXPECT_NEAR(n.at("/vehicle/car"), 250, 2);
  EXPECT_NEAR(n.at("/map/cones"), 20, 1);      // 2 Hz
  EXPECT_EQ(n.at("/camera/image"), 1);         // sent once: no newer picture
  EXPECT_FALSE(n.count("/perception/cones"));  // no detections in these snapshots
  // 5 Hz, plus one at once when the AS state changed in between.
  EXPECT_NEAR(n.at("/as/status"), 51, 1);
  EXPECT_NEAR(n.at("/faults"), 10, 1);  // 1 Hz
}

TEST(ChannelPacer, AChangedKeyIsSentAtOnceAndTheRecordingFollowsTheRunsClock) {
  ChannelPacer pacer(telemetry_channels(), [](const TelemetryChannel& c) { return c.record_hz; });
  const auto faults_row = [&] {
    for (std::size_t i = 0; i < telemetry_channels().size(); ++i)
      if (telemetry_channels()[i].spec.topic == "/faults") return i;
    return std::size_t{0};
  }();
  TelemetrySnapshot s;
  std::vector<Stamp> fault_msgs;
  int states = 0;
  for (int k = 0; k < 250; ++k) {  // 10 s of snapshots at 25 Hz of the run's clock
    s.t = k * 0.04;
    if (k == 100 || k == 101 || k == 180) s.faults.push_back({s.t, "planning", "late " + std::to_string(k), "", true});
    for (const auto i : pacer.due(s, s.t)) {
      if (i == faults_row) fault_msgs.push_back(s.t);
      if (telemetry_channels()[i].spec.topic == "/vehicle/state") ++states;
    }
  }
  EXPECT_EQ(states, 250);  // every snapshot
  // Recorded only when the list changes (the first snapshot's empty list included), each at once.
  EXPECT_EQ(fault_msgs, (std::vector<Stamp>{0.0, 100 * 0.04, 101 * 0.04, 180 * 0.04}));
}

// The localization's rows: the estimate only once the stack has a state, its error only with the truth beside it,
// the loop closures at once when one more closed, the true path only when it grew.
TEST(ChannelPacer, LocalizationRowsSendWhatTheSnapshotHasAndLoopClosuresAtOnce) {
  // Due rows whose builder gives a message (a row without data for a snapshot sends nothing).
  std::map<std::string, int> n;
  ChannelPacer pacer(telemetry_channels(), [](const TelemetryChannel& c) { return c.live_hz; });
  TelemetrySnapshot s;
  for (int tick = 0; tick < 1000; tick += 4) {  // snapshots every 40 ms for 10 s
    s.t = tick * 0.01;
    if (tick == 500) {  // a state from 5 s on
      s.localization.emplace();
      s.localization->source = "fused";
    }
    if (tick == 700) s.truth.emplace();  // the truth from 7 s on
    if (tick == 604) s.loop_closures.emplace_back();  // 6.04 s: between two 1 Hz messages
    if (tick % 100 == 0) s.truth_path = std::make_shared<const std::vector<Vec2>>(2, Vec2(0, 0));  // grew, 1 Hz
    for (const auto i : pacer.due(s, s.t)) {
      const auto& r = telemetry_channels()[i];
      if (r.build && r.build(s, {})) ++n[r.spec.topic];
    }
  }
  EXPECT_NEAR(n["/localization/estimate"], 50, 1);       // 10 Hz over the last 5 s
  EXPECT_NEAR(n["/truth/localization_error"], 30, 1);    // 10 Hz over the last 3 s
  EXPECT_NEAR(n["/localization/loop_closures"], 11, 1);  // 1 Hz, plus one at once
  EXPECT_EQ(n["/truth/path"], 10);                       // each new path once
  TelemetrySnapshot one;
  one.loop_closures.emplace_back();
  one.loop_closures[0].dx = 0.6;
  one.loop_closures[0].dy = 0.8;
  const auto built = row("/localization/loop_closures").build(one, {});
  ASSERT_TRUE(built);
  const auto loops = json::parse(built->json);
  EXPECT_NEAR(loops["loop_closures"][0]["shift"].get<double>(), 1.0, 1e-12);
}

}  // namespace
}  // namespace fsd
