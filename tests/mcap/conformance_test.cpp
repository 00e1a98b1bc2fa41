// The MCAP specification's conformance suite (../shared/data/mcap-conformance): each of its 416 variants is
// written by @mcap/core (tests/mcap/conformance_write.mjs, an independent implementation) and read by ours; the
// linear reader must yield, record for record, what the variant's JSON lists (Message Index records left out, as
// its README says), and the summary reader the same messages.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <tuple>

#include <nlohmann/json.hpp>

#include "common/mcap/byte_io.hpp"
#include "common/mcap/linear_reader.hpp"
#include "common/mcap/summary_reader.hpp"
#include "tests/mcap/node_tools.hpp"
#include "tests/scratch_dir.hpp"

namespace fsd::mcap {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const fs::path kConformance = "../shared/data/mcap-conformance";

// A record in the conformance JSON form: its type and [name, value] pairs sorted by name; integers as decimal
// strings, bytes as lists of decimal strings, maps as objects of strings.
json str(std::uint64_t v) { return std::to_string(v); }
json bytes(const Bytes& b) {
  json a = json::array();
  for (auto x : b) a.push_back(std::to_string(x));
  return a;
}
template <typename K, typename V>
json map(const std::map<K, V>& m) {
  json o = json::object();
  for (const auto& [k, v] : m) {
    if constexpr (std::is_same_v<V, std::string>) {
      o[std::string(k)] = v;
    } else {
      o[std::to_string(k)] = std::to_string(v);
    }
  }
  return o;
}

json conformance_json(const Record& r) {
  std::vector<std::pair<std::string, json>> f;
  std::visit(
      [&](const auto& x) {
        using T = std::decay_t<decltype(x)>;
        if constexpr (std::is_same_v<T, Header>) {
          f = {{"profile", x.profile}, {"library", x.library}};
        } else if constexpr (std::is_same_v<T, Footer>) {
          f = {{"summary_start", str(x.summary_start)},
               {"summary_offset_start", str(x.summary_offset_start)},
               {"summary_crc", str(x.summary_crc)}};
        } else if constexpr (std::is_same_v<T, Schema>) {
          f = {{"id", str(x.id)}, {"name", x.name}, {"encoding", x.encoding}, {"data", bytes(x.data)}};
        } else if constexpr (std::is_same_v<T, Channel>) {
          f = {{"id", str(x.id)},
               {"schema_id", str(x.schema_id)},
               {"topic", x.topic},
               {"message_encoding", x.message_encoding},
               {"metadata", map(x.metadata)}};
        } else if constexpr (std::is_same_v<T, Message>) {
          f = {{"channel_id", str(x.channel_id)},
               {"sequence", str(x.sequence)},
               {"log_time", str(x.log_time)},
               {"publish_time", str(x.publish_time)},
               {"data", bytes(x.data)}};
        } else if constexpr (std::is_same_v<T, ChunkIndex>) {
          f = {{"message_start_time", str(x.message_start_time)},
               {"message_end_time", str(x.message_end_time)},
               {"chunk_start_offset", str(x.chunk_start_offset)},
               {"chunk_length", str(x.chunk_length)},
               {"message_index_offsets", map(x.message_index_offsets)},
               {"message_index_length", str(x.message_index_length)},
               {"compression", x.compression},
               {"compressed_size", str(x.compressed_size)},
               {"uncompressed_size", str(x.uncompressed_size)}};
        } else if constexpr (std::is_same_v<T, Attachment>) {  // the suite leaves the CRC out
          f = {{"log_time", str(x.log_time)},
               {"create_time", str(x.create_time)},
               {"name", x.name},
               {"media_type", x.media_type},
               {"data", bytes(x.data)}};
        } else if constexpr (std::is_same_v<T, AttachmentIndex>) {
          f = {{"offset", str(x.offset)},           {"length", str(x.length)},       {"log_time", str(x.log_time)},
               {"create_time", str(x.create_time)}, {"data_size", str(x.data_size)}, {"name", x.name},
               {"media_type", x.media_type}};
        } else if constexpr (std::is_same_v<T, Statistics>) {
          f = {{"message_count", str(x.message_count)},
               {"schema_count", str(x.schema_count)},
               {"channel_count", str(x.channel_count)},
               {"attachment_count", str(x.attachment_count)},
               {"metadata_count", str(x.metadata_count)},
               {"chunk_count", str(x.chunk_count)},
               {"message_start_time", str(x.message_start_time)},
               {"message_end_time", str(x.message_end_time)},
               {"channel_message_counts", map(x.channel_message_counts)}};
        } else if constexpr (std::is_same_v<T, Metadata>) {
          f = {{"name", x.name}, {"metadata", map(x.metadata)}};
        } else if constexpr (std::is_same_v<T, MetadataIndex>) {
          f = {{"offset", str(x.offset)}, {"length", str(x.length)}, {"name", x.name}};
        } else if constexpr (std::is_same_v<T, SummaryOffset>) {
          f = {{"group_opcode", str(x.group_opcode)},
               {"group_start", str(x.group_start)},
               {"group_length", str(x.group_length)}};
        } else if constexpr (std::is_same_v<T, DataEnd>) {
          f = {{"data_section_crc", str(x.data_section_crc)}};
        } else {
          f = {{"unexpected", to_string(opcode_of(r))}};  // Chunk, MessageIndex: never in the lists
        }
      },
      r);
  std::sort(f.begin(), f.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  json fields = json::array();
  for (auto& [k, v] : f) fields.push_back(json::array({k, v}));
  return {{"type", to_string(opcode_of(r))}, {"fields", fields}};
}

using MessageKey = std::tuple<std::string, std::string, std::string, json>;  // channel, log time, sequence, data

MessageKey key_of(const json& rec) {
  std::map<std::string, json> f;
  for (const auto& p : rec["fields"]) f[p[0].get<std::string>()] = p[1];
  return {f["channel_id"], f["log_time"], f["sequence"], f["data"]};
}

TEST(McapConformance, EveryVariantWrittenByMcapCoreReadsRecordForRecord) {
  ASSERT_TRUE(fs::is_directory(kConformance)) << "run the tests from the project root";
  const fs::path out = fsd::test::scratch_dir() / "conformance";
  std::string log;
  const int rc = test::run_node("tests/mcap/conformance_write.mjs " + kConformance.string() + " " + out.string(), &log);
  if (rc == test::kSkipped) GTEST_SKIP() << log;
  ASSERT_EQ(rc, 0) << log;

  int variants = 0;
  for (const auto& base : fs::directory_iterator(kConformance)) {
    if (!base.is_directory()) continue;
    for (const auto& entry : fs::directory_iterator(base.path())) {
      if (entry.path().extension() != ".json") continue;
      ++variants;
      const std::string name = entry.path().stem().string();
      std::ifstream in(entry.path());
      const json expected = json::parse(in)["records"];

      MappedFile file((out / base.path().filename() / (name + ".mcap")).string());
      ReaderOptions strict;
      strict.strict = true;
      LinearReader reader(file.bytes(), strict);
      json got = json::array();
      std::vector<MessageKey> messages;
      while (auto r = reader.next()) {
        if (std::holds_alternative<MessageIndex>(r->record)) continue;
        got.push_back(conformance_json(r->record));
        if (std::holds_alternative<Message>(r->record)) messages.push_back(key_of(got.back()));
      }
      EXPECT_TRUE(reader.complete()) << name;
      EXPECT_TRUE(reader.issues().empty()) << name << ": " << reader.issues().front().what;
      ASSERT_EQ(got.size(), expected.size()) << name << "\n got: " << got.dump() << "\nwant: " << expected.dump();
      for (std::size_t i = 0; i < got.size(); ++i)
        EXPECT_EQ(got[i], expected[i]) << name << " record " << i << "\n got: " << got[i].dump()
                                       << "\nwant: " << expected[i].dump();

      // The summary reader: the same messages, through the chunk indexes where the variant has them.
      SummaryReader summary(file.bytes(), strict);
      std::vector<MessageKey> via_summary;
      summary.for_each_message(
          [&](const Message& m, const Channel&) { via_summary.push_back(key_of(conformance_json(m))); });
      std::sort(messages.begin(), messages.end());
      std::sort(via_summary.begin(), via_summary.end());
      EXPECT_EQ(via_summary, messages) << name;
      const bool chunk_indexed = name.find("-chx") != std::string::npos;
      EXPECT_EQ(summary.indexed(), chunk_indexed) << name;
    }
  }
  EXPECT_EQ(variants, 416);
}

}  // namespace
}  // namespace fsd::mcap
