// Files written by our writer, read by @mcap/core's independent readers (McapIndexedReader through the summary
// and chunk indexes, McapStreamReader front to back; both validate chunk CRCs): they must find the messages,
// statistics, metadata, attachments and channels we wrote (known from the inputs, not from our reader).
#include <gtest/gtest.h>

#include <cstdio>

#include <nlohmann/json.hpp>

#include "common/mcap/byte_io.hpp"
#include "tests/mcap/node_tools.hpp"
#include "tests/mcap/test_recording.hpp"
#include "tests/scratch_dir.hpp"

namespace fsd::mcap {
namespace {

using nlohmann::json;

std::string hex(const Bytes& b) {
  std::string s;
  char buf[3];
  for (auto x : b) {
    std::snprintf(buf, sizeof buf, "%02x", x);
    s += buf;
  }
  return s;
}

json expected_message(const Message& m) {
  return json::array(
      {m.channel_id, m.sequence, std::to_string(m.log_time), std::to_string(m.publish_time), hex(m.data)});
}

class McapCoreReadsOurs : public ::testing::TestWithParam<Compression> {};

TEST_P(McapCoreReadsOurs, SameMessagesStatisticsMetadataAndIndexes) {
  test::RecordingSpec spec;
  spec.compression = GetParam();
  const auto rec = test::make_recording(spec);
  const std::string path =
      fsd::test::scratch_path(std::string("ours_") + (GetParam() == Compression::Zstd ? "zstd" : "none") + ".mcap");
  {
    FileSink sink(path);
    sink.write(rec.file);
    sink.close();
  }
  std::string out;
  const int rc = test::run_node("tests/mcap/mcap_core_read.mjs " + path, &out);
  if (rc == test::kSkipped) GTEST_SKIP() << out;
  ASSERT_EQ(rc, 0) << out;
  const json got = json::parse(out);
  const json& ix = got["indexed"];

  EXPECT_EQ(ix["header"]["profile"], "fsd");
  EXPECT_EQ(ix["header"]["library"], std::string("fsd-daemon ") + FSD_VERSION);
  const json& st = ix["statistics"];
  EXPECT_EQ(st["message_count"], std::to_string(rec.messages.size()));
  EXPECT_EQ(st["schema_count"], 1);
  EXPECT_EQ(st["channel_count"], 3);
  EXPECT_EQ(st["attachment_count"], 1);
  EXPECT_EQ(st["metadata_count"], 2);
  EXPECT_EQ(st["chunk_count"], rec.chunks.size());
  EXPECT_EQ(st["message_start_time"], std::to_string(rec.messages.front().log_time));
  EXPECT_EQ(st["message_end_time"], std::to_string(rec.messages.back().log_time));
  EXPECT_EQ(st["channel_message_counts"], json({{"1", std::to_string(spec.messages / 3)},
                                                {"2", std::to_string(spec.messages / 3)},
                                                {"3", std::to_string(spec.messages / 3)}}));
  EXPECT_EQ(ix["chunk_indexes"], rec.chunks.size());

  ASSERT_EQ(ix["channels"].size(), 3u);
  EXPECT_EQ(ix["channels"][0]["topic"], "/test/0");
  EXPECT_EQ(ix["channels"][0]["message_encoding"], "fsd.raw");
  EXPECT_EQ(ix["channels"][0]["schema_id"], 0);
  EXPECT_EQ(ix["channels"][1]["message_encoding"], "json");
  EXPECT_EQ(ix["channels"][1]["metadata"], json({{"index", "1"}}));
  ASSERT_EQ(ix["schemas"].size(), 1u);
  EXPECT_EQ(ix["schemas"][0]["encoding"], "jsonschema");
  EXPECT_EQ(json::parse(ix["schemas"][0]["data"].get<std::string>())["type"], "object");

  ASSERT_EQ(ix["metadata"].size(), 2u);
  EXPECT_EQ(ix["metadata"][0]["name"], "fsd.recording");
  EXPECT_EQ(ix["metadata"][1]["metadata"], json({{"dropped", "3"}, {"queue_high_water", "17"}}));
  ASSERT_EQ(ix["attachments"].size(), 1u);
  EXPECT_EQ(ix["attachments"][0]["data"], hex(rec.attachments[0].data));
  EXPECT_EQ(ix["attachments"][0]["media_type"], "text/csv");

  json want = json::array();
  for (const auto& m : rec.messages) want.push_back(expected_message(m));
  EXPECT_EQ(ix["messages"], want);  // log-time order, which is write order here
  EXPECT_EQ(got["stream"]["messages"], want);
  const json& counts = got["stream"]["record_counts"];
  EXPECT_FALSE(counts.contains("Chunk"));  // chunks are opened, not returned
  EXPECT_EQ(counts["MessageIndex"], rec.chunks.size() * 3);
  EXPECT_EQ(counts["ChunkIndex"], rec.chunks.size());
  EXPECT_EQ(counts["Footer"], 1);
  EXPECT_EQ(counts["DataEnd"], 1);
}

INSTANTIATE_TEST_SUITE_P(Compression, McapCoreReadsOurs, ::testing::Values(Compression::Zstd, Compression::None),
                         [](const auto& info) { return info.param == Compression::Zstd ? "zstd" : "none"; });

}  // namespace
}  // namespace fsd::mcap
