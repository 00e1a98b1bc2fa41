// The recorder's own messages (daemon/recording/recording_format.hpp) against bytes worked out by hand from the layout, and
// the decoders' refusals of anything malformed.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "daemon/recording/recorder.hpp"
#include "daemon/recording/recording_format.hpp"

namespace fsd {
namespace {

using Bytes = std::vector<std::uint8_t>;

TEST(RecordingFormat, ACommandIsThirtyFiveLittleEndianBytes) {
  CommandRecord r;
  r.now = 1.5;                 // 0x3FF8000000000000
  r.command.stamp = 2.0;       // 0x4000000000000000
  r.command.steering = -0.25;  // 0xBFD0000000000000
  r.command.target_speed = 0.0;
  r.command.brake_hard = true;
  r.request = wire::vcu::AsRequest::Finished;  // 2
  const Bytes b = encode_command(r);
  const Bytes want = {1, 0, 0, 0, 0, 0,    0,    0xF8, 0x3F, 0, 0, 0, 0, 0, 0, 0x00, 0x40, 0,
                      0, 0, 0, 0, 0, 0xD0, 0xBF, 0,    0,    0, 0, 0, 0, 0, 0, 1,    2};
  EXPECT_EQ(b, want);
  const auto back = decode_command(b);
  ASSERT_TRUE(back);
  EXPECT_EQ(back->now, 1.5);
  EXPECT_EQ(back->command.steering, -0.25);
  EXPECT_TRUE(back->command.brake_hard);
  EXPECT_EQ(back->request, wire::vcu::AsRequest::Finished);

  Bytes shorter(b.begin(), b.end() - 1), longer = b, bad_version = b, bad_request = b, bad_flag = b;
  longer.push_back(0);
  bad_version[0] = 2;
  bad_request[34] = 4;
  bad_flag[33] = 2;
  for (const Bytes& x : {shorter, longer, bad_version, bad_request, bad_flag, Bytes{}}) EXPECT_FALSE(decode_command(x));
}

TEST(RecordingFormat, ACycleMarkerListsItsFramesExactTimes) {
  // 0.1 + 0.2 is not 0.3: the exact double must come back, which nanoseconds would not give.
  const CycleMarker m{0.1 + 0.2, {0.35, 35 * 0.01}};  // cycle 35 of the 100 Hz loop
  const Bytes b = encode_cycle(m);
  ASSERT_EQ(b.size(), 1u + 8 + 4 + 2 * 8);
  EXPECT_EQ(b[0], 1);
  EXPECT_EQ(b[9], 2);  // u32 count, little-endian
  EXPECT_EQ(b[10] | b[11] | b[12], 0);
  const auto back = decode_cycle(b);
  ASSERT_TRUE(back);
  EXPECT_EQ(back->now, 0.1 + 0.2);
  EXPECT_NE(back->now, 0.3);
  ASSERT_EQ(back->frame_times.size(), 2u);
  EXPECT_EQ(back->frame_times[1], 35 * 0.01);
  EXPECT_NE(back->frame_times[1], back->frame_times[0]);
  EXPECT_NE(static_cast<double>(to_ns(35 * 0.01)) / 1e9, 35 * 0.01);  // why the marker carries them

  Bytes cut(b.begin(), b.end() - 3), lying = b;
  lying[9] = 3;  // claims a third time that is not there
  EXPECT_FALSE(decode_cycle(cut));
  EXPECT_FALSE(decode_cycle(lying));
  EXPECT_FALSE(decode_cycle(Bytes{1}));
}

TEST(RecordingFormat, RawTopicsAndSchemasFollowTheChannelNames) {
  EXPECT_EQ(raw_topic(RawChannel::Vlp16Data), "/raw/vlp16_data");
  EXPECT_EQ(raw_schema(RawChannel::Camera), "fsd.raw.jpeg");
  EXPECT_EQ(raw_channel_of_topic("/raw/truth_cones"), RawChannel::TruthCones);
  EXPECT_FALSE(raw_channel_of_topic("/raw/"));
  EXPECT_FALSE(raw_channel_of_topic("/stack/cycle"));
  EXPECT_EQ(to_ns(1.25), 1250000000u);
  EXPECT_EQ(to_ns(-1.0), 0u);
}

TEST(RecordingFormat, TheRunMetadataRoundTripsAndRefusesNonsense) {
  RecordedRun r;
  r.mode = "sim";
  r.lockstep = true;
  r.mission = Mission::Skidpad;
  r.laps = 3;
  r.simulator = true;
  r.start = 0.1 + 0.2;
  r.camera_latency = 0.035;
  r.camera_calibration = "{}";
  const auto m = to_metadata(r);
  EXPECT_EQ(m.at("mission"), "skidpad");
  const RecordedRun back = recorded_run_from_metadata(m);
  EXPECT_EQ(back.mission, Mission::Skidpad);
  EXPECT_EQ(back.laps, 3);
  EXPECT_TRUE(back.lockstep);
  EXPECT_EQ(back.start, 0.1 + 0.2);  // bit for bit
  EXPECT_EQ(back.camera_latency, 0.035);

  auto broken = m;
  broken["laps"] = "two";
  EXPECT_THROW(recorded_run_from_metadata(broken), std::invalid_argument);
  broken = m;
  broken["mode"] = "dream";
  EXPECT_THROW(recorded_run_from_metadata(broken), std::invalid_argument);
  broken = m;
  broken.erase("mission");
  EXPECT_THROW(recorded_run_from_metadata(broken), std::invalid_argument);
}

TEST(RecordingFormat, TheConfigurationIsFlattenedToDottedKeys) {
  const auto flat = flatten_config(nlohmann::json::parse(R"({"a": {"b": 1.5, "c": {"d": "x"}}, "e": [1, 2]})"));
  EXPECT_EQ(flat, (mcap::StringMap{{"a.b", "1.5"}, {"a.c.d", "\"x\""}, {"e", "[1,2]"}}));
}

TEST(RecordingFormat, PartsAreNumberedBesideTheFirstFile) {
  EXPECT_EQ(recording_part_path("runs/today.mcap", 0), "runs/today.mcap");
  EXPECT_EQ(recording_part_path("runs/today.mcap", 1), "runs/today-001.mcap");
  EXPECT_EQ(recording_part_path("today.mcap", 12), "today-012.mcap");
}

}  // namespace
}  // namespace fsd
