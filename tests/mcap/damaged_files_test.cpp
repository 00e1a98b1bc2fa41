// Files cut off mid-write and files with a damaged chunk: the readers keep every complete chunk's messages, say
// where the damage is, never read a damaged chunk as data, and recover() turns what is left into a whole file.
#include <gtest/gtest.h>

#include <set>

#include "common/mcap/linear_reader.hpp"
#include "common/mcap/recover.hpp"
#include "common/mcap/summary_reader.hpp"
#include "tests/mcap/test_recording.hpp"

namespace fsd::mcap {
namespace {

using test::KnownRecording;
using test::make_recording;
using test::RecordingSpec;
using test::same_message;

struct LinearResult {
  std::vector<Message> messages;
  std::vector<Issue> issues;
  std::optional<std::uint64_t> truncated_at;
  bool complete = false;
};

LinearResult read_linear(std::span<const std::uint8_t> file, ReaderOptions options = {}) {
  LinearReader reader(file, options);
  LinearResult out;
  while (auto r = reader.next())
    if (auto* m = std::get_if<Message>(&r->record)) out.messages.push_back(*m);
  out.issues = reader.issues();
  out.truncated_at = reader.truncated_at();
  out.complete = reader.complete();
  return out;
}

// The messages of the chunks that end at or before `cut`, in order: what must survive a cut there.
std::vector<Message> messages_of_chunks_before(const KnownRecording& rec, const std::vector<ChunkIndex>& chunks,
                                               std::uint64_t cut) {
  std::vector<Message> out;
  for (std::size_t k = 0; k < chunks.size(); ++k)
    if (chunks[k].chunk_start_offset + chunks[k].chunk_length <= cut)
      for (int i : rec.chunks[k]) out.push_back(rec.messages[static_cast<std::size_t>(i)]);
  return out;
}

void expect_same(const std::vector<Message>& got, const std::vector<Message>& want, const std::string& where) {
  ASSERT_EQ(got.size(), want.size()) << where;
  for (std::size_t i = 0; i < got.size(); ++i) ASSERT_TRUE(same_message(got[i], want[i])) << where << " #" << i;
}

class McapTruncated : public ::testing::TestWithParam<Compression> {
 protected:
  void SetUp() override {
    RecordingSpec spec;
    spec.compression = GetParam();
    spec.messages = 300;
    rec_ = make_recording(spec);
    SummaryReader full(rec_.file);
    ASSERT_TRUE(full.has_summary());
    chunks_ = full.summary()->chunk_indexes;
    summary_start_ = full.summary()->footer.summary_start;
    ASSERT_EQ(chunks_.size(), rec_.chunks.size());
    ASSERT_GT(chunks_.size(), 5u);
  }

  // Cut the file at `cut`: the linear reader, then recover() and the summary reader on the recovered file.
  void check_cut(std::uint64_t cut) {
    const std::string where = "cut at " + std::to_string(cut);
    const std::span<const std::uint8_t> part(rec_.file.data(), cut);
    const auto want = messages_of_chunks_before(rec_, chunks_, cut);

    const auto got = read_linear(part);
    expect_same(got.messages, want, where);
    EXPECT_FALSE(got.complete) << where;
    ASSERT_TRUE(got.truncated_at) << where;
    EXPECT_LE(*got.truncated_at, cut) << where;
    ASSERT_FALSE(got.issues.empty());
    EXPECT_EQ(got.issues.back().kind, Issue::Kind::Truncated) << where;
    EXPECT_NE(got.issues.back().what.find("truncated at offset " + std::to_string(*got.truncated_at)),
              std::string::npos)
        << got.issues.back().what;

    BufferSink out;
    const auto report = recover(part, out);
    EXPECT_EQ(report.messages, want.size()) << where;
    EXPECT_EQ(report.bytes_lost, cut - *got.truncated_at) << where;
    EXPECT_FALSE(report.input_complete);
    SummaryReader recovered(out.data);
    ASSERT_TRUE(recovered.has_summary()) << where << ": " << recovered.summary_problem();
    EXPECT_EQ(recovered.summary()->header.profile, "fsd");
    EXPECT_EQ(recovered.summary()->statistics->message_count, want.size());
    if (!want.empty()) {
      EXPECT_TRUE(recovered.indexed()) << where;
    }
    std::vector<Message> again;
    recovered.for_each_message([&](const Message& m, const Channel&) { again.push_back(m); });
    expect_same(again, want, where + " (recovered)");
    EXPECT_TRUE(recovered.issues().empty());
    const auto relinear = read_linear(out.data);
    EXPECT_TRUE(relinear.complete);
    EXPECT_TRUE(relinear.issues.empty()) << where << ": " << relinear.issues.front().what;
  }

  KnownRecording rec_;
  std::vector<ChunkIndex> chunks_;
  std::uint64_t summary_start_ = 0;
};

TEST_P(McapTruncated, AtEveryChunkBoundary) {
  for (const auto& c : chunks_) {
    check_cut(c.chunk_start_offset);                   // just before the chunk
    check_cut(c.chunk_start_offset + c.chunk_length);  // just after it, before its message indexes
  }
}

TEST_P(McapTruncated, InsideChunks) {
  for (const auto& c : chunks_) {
    check_cut(c.chunk_start_offset + 1);
    check_cut(c.chunk_start_offset + 9);  // opcode and length there, the fields not
    check_cut(c.chunk_start_offset + c.chunk_length / 2);
    check_cut(c.chunk_start_offset + c.chunk_length - 1);
  }
}

TEST_P(McapTruncated, InsideTheSummaryAndFooter) {
  const std::uint64_t size = rec_.file.size();
  for (std::uint64_t cut : {summary_start_, summary_start_ + 1, summary_start_ + 40, (summary_start_ + size) / 2,
                            size - 30, size - 9, size - 1}) {
    check_cut(cut);
  }
}

TEST_P(McapTruncated, RightAfterTheMagicAndInsideTheHeader) {
  for (std::size_t cut : {8, 12}) {
    const std::span<const std::uint8_t> part(rec_.file.data(), cut);
    const auto got = read_linear(part);
    EXPECT_TRUE(got.messages.empty());
    ASSERT_TRUE(got.truncated_at);
    EXPECT_EQ(*got.truncated_at, 8u);
    BufferSink out;
    EXPECT_THROW(recover(part, out), McapError);  // not even a header: nothing to recover
  }
}

INSTANTIATE_TEST_SUITE_P(Compression, McapTruncated, ::testing::Values(Compression::Zstd, Compression::None),
                         [](const auto& info) { return info.param == Compression::Zstd ? "zstd" : "none"; });

class McapCorruptChunk : public ::testing::TestWithParam<Compression> {};

TEST_P(McapCorruptChunk, IsReportedWithItsOffsetAndSkipped) {
  RecordingSpec spec;
  spec.compression = GetParam();
  spec.messages = 300;
  auto rec = make_recording(spec);
  const auto chunks = SummaryReader(rec.file).summary()->chunk_indexes;
  const std::size_t bad = 3;
  const auto& ci = chunks[bad];
  // A byte in the middle of the stored (compressed) records.
  rec.file[ci.chunk_start_offset + ci.chunk_length - ci.compressed_size / 2] ^= 0x5A;

  std::vector<Message> want;
  for (std::size_t k = 0; k < chunks.size(); ++k)
    if (k != bad)
      for (int i : rec.chunks[k]) want.push_back(rec.messages[static_cast<std::size_t>(i)]);

  const auto got = read_linear(rec.file);
  expect_same(got.messages, want, "linear");
  EXPECT_TRUE(got.complete);
  ASSERT_GE(got.issues.size(), 1u);
  const Issue& issue = got.issues.front();
  EXPECT_TRUE(issue.kind == Issue::Kind::ChunkCrc || issue.kind == Issue::Kind::ChunkDamaged) << issue.what;
  if (GetParam() == Compression::None) {
    EXPECT_EQ(issue.kind, Issue::Kind::ChunkCrc);
  }
  EXPECT_EQ(issue.offset, ci.chunk_start_offset);
  EXPECT_NE(issue.what.find("chunk at offset " + std::to_string(ci.chunk_start_offset)), std::string::npos)
      << issue.what;
  // The data section's CRC covers the flipped byte too.
  EXPECT_EQ(got.issues.back().kind, Issue::Kind::DataCrc);

  SummaryReader indexed(rec.file);
  ASSERT_TRUE(indexed.indexed());
  std::vector<Message> via_index;
  indexed.for_each_message([&](const Message& m, const Channel&) { via_index.push_back(m); });
  expect_same(via_index, want, "indexed");
  ASSERT_EQ(indexed.issues().size(), 1u);
  EXPECT_EQ(indexed.issues()[0].offset, ci.chunk_start_offset);

  BufferSink out;
  const auto report = recover(rec.file, out);
  EXPECT_EQ(report.chunks_lost, 1u);
  EXPECT_EQ(report.messages, want.size());
  EXPECT_TRUE(report.input_complete);
  std::vector<Message> recovered;
  SummaryReader(out.data).for_each_message([&](const Message& m, const Channel&) { recovered.push_back(m); });
  expect_same(recovered, want, "recovered");
}

TEST_P(McapCorruptChunk, StrictModeRefusesTheFile) {
  RecordingSpec spec;
  spec.compression = GetParam();
  spec.messages = 300;
  auto rec = make_recording(spec);
  const auto ci = SummaryReader(rec.file).summary()->chunk_indexes[2];
  rec.file[ci.chunk_start_offset + ci.chunk_length - ci.compressed_size / 2] ^= 0x5A;
  ReaderOptions strict;
  strict.strict = true;
  const std::string offset = "chunk at offset " + std::to_string(ci.chunk_start_offset);
  try {
    read_linear(rec.file, strict);
    ADD_FAILURE() << "strict linear read accepted a damaged chunk";
  } catch (const McapError& e) {
    EXPECT_NE(std::string(e.what()).find(offset), std::string::npos) << e.what();
  }
  SummaryReader indexed(rec.file, strict);
  EXPECT_THROW(indexed.for_each_message([](const Message&, const Channel&) {}), McapError);
}

INSTANTIATE_TEST_SUITE_P(Compression, McapCorruptChunk, ::testing::Values(Compression::Zstd, Compression::None),
                         [](const auto& info) { return info.param == Compression::Zstd ? "zstd" : "none"; });

TEST(McapDamagedSummary, ASummaryThatFailsItsCrcIsNotUsedAndTheLinearScanStandsIn) {
  RecordingSpec spec;
  spec.messages = 120;
  auto rec = make_recording(spec);
  const auto summary_start = SummaryReader(rec.file).summary()->footer.summary_start;
  rec.file[summary_start + 20] ^= 0x01;  // inside the first summary record
  SummaryReader reader(rec.file);
  EXPECT_FALSE(reader.has_summary());
  EXPECT_EQ(reader.summary_problem(), "summary CRC mismatch");
  EXPECT_FALSE(reader.indexed());
  std::vector<Message> got;
  reader.for_each_message([&](const Message& m, const Channel&) { got.push_back(m); });
  expect_same(got, rec.messages, "linear fallback");
}

TEST(McapCorruptChunk, ALyingChunkLengthInTheIndexIsNotFollowed) {
  RecordingSpec spec;
  spec.messages = 100;
  auto rec = make_recording(spec);
  // Chunk records claiming more bytes than the file has: the linear reader reports a cut-off file.
  const auto ci = SummaryReader(rec.file).summary()->chunk_indexes[1];
  for (int i = 0; i < 8; ++i) rec.file[ci.chunk_start_offset + 1 + i] = 0xFF;
  const auto got = read_linear(rec.file);
  ASSERT_TRUE(got.truncated_at);
  EXPECT_EQ(*got.truncated_at, ci.chunk_start_offset);
  SummaryReader indexed(rec.file);
  std::size_t n = 0;
  indexed.for_each_message([&](const Message&, const Channel&) { ++n; });
  EXPECT_EQ(n, rec.messages.size() - rec.chunks[1].size());
  ASSERT_EQ(indexed.issues().size(), 1u);
  EXPECT_EQ(indexed.issues()[0].offset, ci.chunk_start_offset);
}

}  // namespace
}  // namespace fsd::mcap
