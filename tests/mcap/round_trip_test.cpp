// What the writer writes, both readers read back: records, statistics, indexes, metadata and attachments, with
// and without compression, over many chunks.
#include <gtest/gtest.h>

#include <set>

#include "common/mcap/linear_reader.hpp"
#include "common/mcap/summary_reader.hpp"
#include "tests/mcap/test_recording.hpp"

namespace fsd::mcap {
namespace {

using test::make_recording;
using test::RecordingSpec;
using test::same_message;

class McapRoundTrip : public ::testing::TestWithParam<Compression> {};

TEST_P(McapRoundTrip, LinearReaderYieldsEveryRecordWritten) {
  RecordingSpec spec;
  spec.compression = GetParam();
  const auto rec = make_recording(spec);
  ASSERT_GT(rec.chunks.size(), 10u) << "the test needs many chunks";

  LinearReader reader(rec.file);
  std::vector<Message> messages;
  std::vector<Metadata> metadata;
  std::vector<Attachment> attachments;
  std::vector<Opcode> order;
  int schemas = 0, channels = 0;
  while (auto r = reader.next()) {
    order.push_back(opcode_of(r->record));
    if (auto* m = std::get_if<Message>(&r->record)) {
      EXPECT_TRUE(r->in_chunk);
      messages.push_back(*m);
    }
    if (auto* m = std::get_if<Metadata>(&r->record)) metadata.push_back(*m);
    if (auto* a = std::get_if<Attachment>(&r->record)) attachments.push_back(*a);
    if (std::holds_alternative<Schema>(r->record)) ++schemas;
    if (auto* c = std::get_if<Channel>(&r->record)) {
      ++channels;
      EXPECT_EQ(c->metadata.at("index"), std::to_string(c->id - 1));
    }
  }
  EXPECT_TRUE(reader.complete());
  EXPECT_FALSE(reader.truncated_at());
  EXPECT_TRUE(reader.issues().empty()) << reader.issues().front().what;
  EXPECT_EQ(reader.chunks_read(), rec.chunks.size());
  ASSERT_EQ(messages.size(), rec.messages.size());
  for (std::size_t i = 0; i < messages.size(); ++i) EXPECT_TRUE(same_message(messages[i], rec.messages[i])) << i;
  ASSERT_EQ(metadata.size(), 2u);
  EXPECT_EQ(metadata[0].metadata, rec.metadata[0].metadata);
  EXPECT_EQ(metadata[1].metadata, rec.metadata[1].metadata);
  ASSERT_EQ(attachments.size(), 1u);
  EXPECT_EQ(attachments[0].data, rec.attachments[0].data);
  EXPECT_EQ(attachments[0].media_type, "text/csv");
  EXPECT_EQ(attachments[0].create_time, 8u);
  // Schemas and channels once in the data section and once in the summary.
  EXPECT_EQ(schemas, 2);
  EXPECT_EQ(channels, 6);
  EXPECT_EQ(order.front(), Opcode::Header);
  EXPECT_EQ(order.back(), Opcode::Footer);
  // Each chunk is followed by one message index per channel that has messages in it.
  EXPECT_EQ(std::count(order.begin(), order.end(), Opcode::MessageIndex), static_cast<long>(rec.chunks.size() * 3));
}

TEST_P(McapRoundTrip, SummaryHasStatisticsAndIndexesOfWhatWasWritten) {
  RecordingSpec spec;
  spec.compression = GetParam();
  const auto rec = make_recording(spec);
  SummaryReader reader(rec.file);
  ASSERT_TRUE(reader.has_summary()) << reader.summary_problem();
  ASSERT_TRUE(reader.indexed());
  const Summary& s = *reader.summary();
  EXPECT_EQ(s.header.profile, "fsd");
  EXPECT_EQ(s.header.library, std::string("fsd-daemon ") + FSD_VERSION);
  ASSERT_TRUE(s.statistics);
  EXPECT_EQ(s.statistics->message_count, rec.messages.size());
  EXPECT_EQ(s.statistics->schema_count, 1u);
  EXPECT_EQ(s.statistics->channel_count, 3u);
  EXPECT_EQ(s.statistics->metadata_count, 2u);
  EXPECT_EQ(s.statistics->attachment_count, 1u);
  EXPECT_EQ(s.statistics->chunk_count, rec.chunks.size());
  EXPECT_EQ(s.statistics->message_start_time, rec.messages.front().log_time);
  EXPECT_EQ(s.statistics->message_end_time, rec.messages.back().log_time);
  for (std::uint16_t c = 1; c <= 3; ++c) EXPECT_EQ(s.statistics->channel_message_counts.at(c), rec.messages.size() / 3);
  EXPECT_EQ(s.channels.size(), 3u);
  EXPECT_EQ(s.schemas.at(1).encoding, "jsonschema");
  EXPECT_EQ(s.metadata_indexes.size(), 2u);
  EXPECT_EQ(s.attachment_indexes.size(), 1u);
  EXPECT_EQ(s.attachment_indexes[0].data_size, rec.attachments[0].data.size());
  ASSERT_EQ(s.chunk_indexes.size(), rec.chunks.size());
  for (std::size_t k = 0; k < rec.chunks.size(); ++k) {
    const auto& ci = s.chunk_indexes[k];
    EXPECT_EQ(ci.compression, to_string(GetParam()));
    EXPECT_EQ(ci.message_start_time, rec.messages[static_cast<std::size_t>(rec.chunks[k].front())].log_time);
    EXPECT_EQ(ci.message_end_time, rec.messages[static_cast<std::size_t>(rec.chunks[k].back())].log_time);
    // The chunk record starts where the index says: its opcode is there.
    ASSERT_LT(ci.chunk_start_offset, rec.file.size());
    EXPECT_EQ(rec.file[ci.chunk_start_offset], static_cast<std::uint8_t>(Opcode::Chunk));
    EXPECT_EQ(ci.message_index_offsets.size(), 3u);
  }
  // The summary offsets point at groups of their own opcode.
  std::set<int> groups;
  for (const auto& g : s.summary_offsets) {
    groups.insert(g.group_opcode);
    EXPECT_EQ(rec.file[g.group_start], g.group_opcode);
  }
  EXPECT_EQ(groups, (std::set<int>{0x03, 0x04, 0x08, 0x0A, 0x0B, 0x0D}));
}

TEST_P(McapRoundTrip, MessagesThroughTheChunkIndexesEqualTheInput) {
  RecordingSpec spec;
  spec.compression = GetParam();
  const auto rec = make_recording(spec);
  SummaryReader reader(rec.file);
  std::vector<Message> got;
  reader.for_each_message([&](const Message& m, const Channel& c) {
    EXPECT_EQ(c.id, m.channel_id);
    got.push_back(m);
  });
  EXPECT_TRUE(reader.indexed());
  EXPECT_TRUE(reader.issues().empty());
  ASSERT_EQ(got.size(), rec.messages.size());
  for (std::size_t i = 0; i < got.size(); ++i) EXPECT_TRUE(same_message(got[i], rec.messages[i])) << i;
}

INSTANTIATE_TEST_SUITE_P(Compression, McapRoundTrip, ::testing::Values(Compression::Zstd, Compression::None),
                         [](const auto& info) { return info.param == Compression::Zstd ? "zstd" : "none"; });

TEST(McapWriter, ZstdChunksAreSmallerThanTheirRecords) {
  RecordingSpec spec;
  const auto zstd = make_recording(spec);
  spec.compression = Compression::None;
  const auto none = make_recording(spec);
  EXPECT_LT(zstd.file.size() * 2, none.file.size());  // the payloads are periodic: zstd must see it
}

TEST(McapWriter, WriterDroppedWithoutCloseLeavesAWholeFile) {
  BufferSink sink;
  {
    Writer w(sink);
    const auto ch = w.add_channel("/a", "fsd.raw", 0);
    const Bytes data{1, 2, 3};
    w.write_message(ch, 10, 10, data);
    w.write_message(ch, 20, 20, data);
  }
  SummaryReader reader(sink.data);
  ASSERT_TRUE(reader.has_summary()) << reader.summary_problem();
  EXPECT_EQ(reader.summary()->statistics->message_count, 2u);
  std::vector<std::uint32_t> seqs;
  reader.for_each_message([&](const Message& m, const Channel&) { seqs.push_back(m.sequence); });
  EXPECT_EQ(seqs, (std::vector<std::uint32_t>{0, 1}));
}

TEST(McapWriter, BytesWrittenGrowsByChunk) {
  BufferSink sink;
  WriterOptions o;
  o.chunk_size = 4096;
  Writer w(sink, o);
  const auto ch = w.add_channel("/a", "fsd.raw", 0);
  const std::uint64_t start = w.bytes_written();
  EXPECT_EQ(start, sink.data.size());
  const Bytes data(1000, 7);
  for (int i = 0; i < 3; ++i) w.write_message(ch, i, i, data);
  EXPECT_EQ(w.bytes_written(), start);  // still in the open chunk
  EXPECT_EQ(w.bytes_pending(), 3 * (test::kMessageRecordOverhead + 1000));
  w.write_message(ch, 3, 3, data);  // crosses 4096: the chunk is written
  EXPECT_GT(w.bytes_written(), start);
  EXPECT_EQ(w.bytes_written(), sink.data.size());
  EXPECT_EQ(w.bytes_pending(), 0u);
}

TEST(McapWriter, RejectsUnknownIds) {
  BufferSink sink;
  Writer w(sink);
  EXPECT_THROW(w.add_channel("/a", "json", 5), McapError);
  EXPECT_THROW(w.write_message(9, 0, 0, Bytes{}), McapError);
  const auto s = w.add_schema("x", "jsonschema", Bytes{});
  EXPECT_THROW(w.add_schema(Schema{s, "y", "jsonschema", {}}), McapError);
  EXPECT_THROW(w.add_schema(Schema{0, "y", "jsonschema", {}}), McapError);
}

}  // namespace
}  // namespace fsd::mcap
