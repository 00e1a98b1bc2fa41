// A recording made by `fsd run --sim --record` (the recorder's thread, splitting, metadata, attachment) read by
// @mcap/core's independent readers (tests/mcap/mcap_core_read.mjs): the counts the run reported, one command per
// cycle marker, the derived JSON channels, the configuration the run was given, and the track attached byte for byte as it is on disk.
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <sstream>

#include <nlohmann/json.hpp>

#include "tests/daemon/fsd_process.hpp"
#include "tests/mcap/node_tools.hpp"
#include "tests/scratch_dir.hpp"
#include "tests/truth_sources.hpp"

namespace fsd::mcap {
namespace {

using nlohmann::json;

std::string hex_of_file(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::ostringstream s;
  s << f.rdbuf();
  std::string h;
  char b[3];
  for (unsigned char c : s.str()) {
    std::snprintf(b, sizeof b, "%02x", c);
    h += b;
  }
  return h;
}

TEST(McapCoreReadsRecording, AFileRecordedByTheDaemon) {
  const std::string track = "../shared/tracks/epfl_acceleration.csv";
  const std::string file = fsd::test::scratch_path("daemon_recorded.mcap");
  const std::string report = fsd::test::scratch_path("daemon_recorded.json");
  const std::string cfg = fsd::test::scratch_path("daemon_recorded_cfg.json");
  std::ofstream(cfg) << fsd::test::truth_sources({{"run", {{"max_sim_time", 2.0}}}});
  std::string out;
  ASSERT_EQ(fsd::test::run_fsd("run --sim --headless --mission acceleration --track " + track + " --config " + cfg +
                                   " --record " + file + " --report " + report,
                               &out),
            0)
      << out;
  json rec;
  std::ifstream(report) >> rec;
  rec = rec["recording"];

  const int rc = test::run_node("tests/mcap/mcap_core_read.mjs " + file, &out);
  if (rc == test::kSkipped) GTEST_SKIP() << out;
  ASSERT_EQ(rc, 0) << out.substr(0, 2000);
  const json got = json::parse(out);
  const json& ix = got["indexed"];
  EXPECT_EQ(ix["header"]["profile"], "fsd");
  const auto total = rec["frames_written"].get<std::uint64_t>() + rec["cycles_written"].get<std::uint64_t>() +
                     rec["commands_written"].get<std::uint64_t>() + rec["derived_written"].get<std::uint64_t>();
  EXPECT_EQ(ix["statistics"]["message_count"], std::to_string(total));
  EXPECT_EQ(ix["messages"].size(), total);
  EXPECT_EQ(got["stream"]["messages"].size(), total);

  std::map<int, std::string> topic_of;
  for (const auto& c : ix["channels"]) topic_of[c["id"].get<int>()] = c["topic"].get<std::string>();
  std::map<std::string, std::uint64_t> per_topic;
  for (const auto& m : ix["messages"]) ++per_topic[topic_of[m[0].get<int>()]];
  // 2 s at 100 Hz: 200 cycles, each with its command and the truth state it was fed.
  EXPECT_EQ(per_topic["/stack/cycle"], 200u);
  EXPECT_EQ(per_topic["/stack/command"], 200u);
  EXPECT_EQ(per_topic["/raw/truth_state"], 200u);
  EXPECT_EQ(per_topic["/raw/truth_cones"], 1u);  // no cone fell
  EXPECT_GT(per_topic["/raw/nmea"], 0u);
  EXPECT_GT(per_topic["/raw/vcu_rx"], 0u);
  // The derived channels for Foxglove Studio: the state at every snapshot (every 4th cycle), the log.
  EXPECT_EQ(per_topic["/vehicle/state"], 50u);
  EXPECT_EQ(per_topic["/vehicle/car"], 50u);
  EXPECT_GT(per_topic["/as/status"], 0u);
  EXPECT_GT(per_topic["/log"], 0u);

  std::map<std::string, json> metadata;
  for (const auto& m : ix["metadata"]) metadata[m["name"].get<std::string>()] = m["metadata"];
  EXPECT_EQ(metadata["fsd.recording"]["fsd.recording_version"], "1");
  EXPECT_EQ(metadata["fsd.config"]["run.mission"], "\"acceleration\"");
  EXPECT_EQ(metadata["fsd.config"]["run.max_sim_time"], "2.0");
  EXPECT_EQ(metadata["fsd.config"]["sim.enable_lidar"], "false");
  EXPECT_EQ(metadata["fsd.run"]["mode"], "sim");
  EXPECT_EQ(metadata["fsd.run"]["lockstep"], "true");
  EXPECT_EQ(metadata["fsd.recorder"]["dropped"], "0");
  ASSERT_EQ(ix["attachments"].size(), 1u);
  EXPECT_EQ(ix["attachments"][0]["name"], "track.csv");
  EXPECT_EQ(ix["attachments"][0]["data"], hex_of_file(track));
}

}  // namespace
}  // namespace fsd::mcap
