#pragma once
// A recording with known content for the MCAP tests: the messages are generated from their index, so a test
// knows exactly what each one holds and in which chunk the writer had to put it (a chunk closes once its records
// reach the chunk size; the message record of payload n is 31 + n bytes).
#include <cstdint>
#include <string>
#include <vector>

#include "common/mcap/records.hpp"
#include "common/mcap/writer.hpp"

namespace fsd::mcap::test {

struct RecordingSpec {
  int channels = 3;
  int messages = 600;
  Compression compression = Compression::Zstd;
  std::uint64_t chunk_size = 8 * 1024;
  bool metadata = true;
  bool attachment = true;
};

struct KnownRecording {
  Bytes file;
  std::vector<Message> messages;         // in write order
  std::vector<std::vector<int>> chunks;  // message indices of each chunk, as the writer must cut them
  std::vector<Metadata> metadata;
  std::vector<Attachment> attachments;
};

inline constexpr std::uint64_t kMessageRecordOverhead = 9 + 2 + 4 + 8 + 8;

inline Bytes payload_of(int i) {
  Bytes b(static_cast<std::size_t>(40 + (i * 37) % 300));
  for (std::size_t k = 0; k < b.size(); ++k) b[k] = static_cast<std::uint8_t>(i * 131 + k * 7);
  return b;
}

inline KnownRecording make_recording(const RecordingSpec& spec) {
  KnownRecording out;
  BufferSink sink;
  WriterOptions options;
  options.compression = spec.compression;
  options.chunk_size = spec.chunk_size;
  {
    Writer w(sink, options);
    const std::string schema_text = R"({"type":"object","properties":{"v":{"type":"number"}}})";
    const auto json_schema = w.add_schema("fsd.Test", "jsonschema", Bytes(schema_text.begin(), schema_text.end()));
    std::vector<std::uint16_t> channels;
    for (int c = 0; c < spec.channels; ++c)
      channels.push_back(w.add_channel("/test/" + std::to_string(c), c == 0 ? "fsd.raw" : "json",
                                       c == 0 ? 0 : json_schema, {{"index", std::to_string(c)}}));
    if (spec.metadata) {
      out.metadata.push_back(Metadata{"fsd.recording", {{"fsd.recording_version", "1"}}});
      w.write_metadata(out.metadata.back().name, out.metadata.back().metadata);
    }
    std::uint64_t in_chunk = 0;
    std::vector<std::uint32_t> seq(channels.size(), 0);
    for (int i = 0; i < spec.messages; ++i) {
      Message m;
      m.channel_id = channels[static_cast<std::size_t>(i % spec.channels)];
      m.sequence = seq[static_cast<std::size_t>(i % spec.channels)]++;
      m.log_time = 1'000'000'000ull + static_cast<std::uint64_t>(i) * 1'000'000ull;
      m.publish_time = m.log_time - 500;
      m.data = payload_of(i);
      w.write_message(m.channel_id, m.log_time, m.publish_time, m.data);
      if (in_chunk == 0) out.chunks.emplace_back();
      out.chunks.back().push_back(i);
      in_chunk += kMessageRecordOverhead + m.data.size();
      if (in_chunk >= spec.chunk_size) in_chunk = 0;
      out.messages.push_back(std::move(m));
    }
    if (spec.attachment) {
      Attachment a;
      a.name = "track.csv";
      a.media_type = "text/csv";
      a.log_time = 7;
      a.create_time = 8;
      const std::string text = "tag,x,y\nblue,1,2\n";
      a.data.assign(text.begin(), text.end());
      out.attachments.push_back(a);
      w.write_attachment(a);
      if (!out.chunks.empty() && in_chunk != 0) in_chunk = 0;  // the attachment closed the open chunk
    }
    if (spec.metadata) {
      out.metadata.push_back(Metadata{"fsd.recorder", {{"dropped", "3"}, {"queue_high_water", "17"}}});
      w.write_metadata(out.metadata.back().name, out.metadata.back().metadata);
    }
    w.close();
  }
  out.file = std::move(sink.data);
  return out;
}

inline bool same_message(const Message& a, const Message& b) {
  return a.channel_id == b.channel_id && a.sequence == b.sequence && a.log_time == b.log_time &&
         a.publish_time == b.publish_time && a.data == b.data;
}

}  // namespace fsd::mcap::test
