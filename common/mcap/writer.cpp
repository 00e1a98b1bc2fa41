#include "common/mcap/writer.hpp"

#include <algorithm>
#include <limits>

#include "common/mcap/codec.hpp"
#include "common/mcap/crc32.hpp"

namespace fsd::mcap {

std::string library_name() { return std::string("fsd-daemon ") + FSD_VERSION; }

Writer::Writer(ByteSink& sink, WriterOptions options) : sink_(sink), options_(std::move(options)) {
  if (options_.chunk_size == 0) throw McapError("chunk size must be at least 1 byte");
  emit(kMagic);
  emit_record(Header{options_.profile, options_.library});
}

Writer::~Writer() {
  try {
    close();
  } catch (...) {  // a destructor cannot report: close() explicitly to see the error
  }
}

void Writer::check_ok() const {
  if (!failure_.empty()) throw McapError(failure_);
  if (closed_) throw McapError("the MCAP writer is closed");
}

void Writer::emit(std::span<const std::uint8_t> bytes) {
  try {
    sink_.write(bytes);
  } catch (const McapError& e) {
    failure_ = e.what();
    throw;
  }
  if (in_data_section_) data_crc_ = crc32_update(data_crc_, bytes);
  offset_ += bytes.size();
}

void Writer::emit_record(const Record& r) {
  Bytes b;
  append_record(b, r);
  emit(b);
}

std::uint16_t Writer::add_schema(const std::string& name, const std::string& encoding,
                                 std::span<const std::uint8_t> data) {
  std::uint16_t id = schemas_.empty() ? 1 : static_cast<std::uint16_t>(schemas_.rbegin()->first + 1);
  if (id == 0) throw McapError("no schema id left (65535 schemas)");
  add_schema(Schema{id, name, encoding, Bytes(data.begin(), data.end())});
  return id;
}

std::uint16_t Writer::add_channel(const std::string& topic, const std::string& message_encoding,
                                  std::uint16_t schema_id, const StringMap& metadata) {
  std::uint16_t id = channels_.empty() ? 1 : static_cast<std::uint16_t>(channels_.rbegin()->first + 1);
  if (id == 0) throw McapError("no channel id left (65535 channels)");
  add_channel(Channel{id, schema_id, topic, message_encoding, metadata});
  return id;
}

void Writer::add_schema(const Schema& schema) {
  check_ok();
  if (schema.id == 0) throw McapError("schema id 0 is reserved (it means: no schema)");
  if (schemas_.count(schema.id)) throw McapError("schema id " + std::to_string(schema.id) + " is already taken");
  emit_record(schema);
  schemas_.emplace(schema.id, schema);
  ++stats_.schema_count;
}

void Writer::add_channel(const Channel& channel) {
  check_ok();
  if (channels_.count(channel.id)) throw McapError("channel id " + std::to_string(channel.id) + " is already taken");
  if (channel.schema_id != 0 && !schemas_.count(channel.schema_id))
    throw McapError("channel " + channel.topic + ": unknown schema id " + std::to_string(channel.schema_id));
  emit_record(channel);
  channels_.emplace(channel.id, channel);
  ++stats_.channel_count;
}

void Writer::write_message(std::uint16_t channel_id, Timestamp log_time, Timestamp publish_time,
                           std::span<const std::uint8_t> data) {
  const auto it = next_sequence_.find(channel_id);
  append_message(channel_id, it == next_sequence_.end() ? 0 : it->second, log_time, publish_time, data);
}

void Writer::write_message(const Message& m) {
  append_message(m.channel_id, m.sequence, m.log_time, m.publish_time, m.data);
}

void Writer::append_message(std::uint16_t channel_id, std::uint32_t sequence, Timestamp log_time,
                            Timestamp publish_time, std::span<const std::uint8_t> data) {
  check_ok();
  if (!channels_.count(channel_id)) throw McapError("message on unknown channel id " + std::to_string(channel_id));
  next_sequence_[channel_id] = sequence + 1;

  // Opcode, length, then the fields, straight into the chunk: no Message copy of the payload on the way.
  const std::uint64_t offset_in_chunk = chunk_.size();
  const std::uint64_t body = 2 + 4 + 8 + 8 + data.size();
  chunk_.push_back(static_cast<std::uint8_t>(Opcode::Message));
  auto put = [this](std::uint64_t v, int n) {
    for (int i = 0; i < n; ++i) chunk_.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
  };
  put(body, 8);
  put(channel_id, 2);
  put(sequence, 4);
  put(log_time, 8);
  put(publish_time, 8);
  chunk_.insert(chunk_.end(), data.begin(), data.end());

  auto& index = chunk_indexes_by_channel_[channel_id];
  index.channel_id = channel_id;
  index.records.emplace_back(log_time, offset_in_chunk);
  if (offset_in_chunk == 0) {
    chunk_start_ = chunk_end_ = log_time;
  } else {
    chunk_start_ = std::min(chunk_start_, log_time);
    chunk_end_ = std::max(chunk_end_, log_time);
  }

  if (stats_.message_count == 0) {
    stats_.message_start_time = stats_.message_end_time = log_time;
  } else {
    stats_.message_start_time = std::min(stats_.message_start_time, log_time);
    stats_.message_end_time = std::max(stats_.message_end_time, log_time);
  }
  ++stats_.message_count;
  ++stats_.channel_message_counts[channel_id];

  if (chunk_.size() >= options_.chunk_size) flush_chunk();
}

void Writer::write_metadata(const std::string& name, const StringMap& values) {
  check_ok();
  flush_chunk();  // metadata sits between chunks, never inside one
  const std::uint64_t at = offset_;
  emit_record(Metadata{name, values});
  metadata_indexes_.push_back(MetadataIndex{at, offset_ - at, name});
  ++stats_.metadata_count;
}

void Writer::write_attachment(const Attachment& a) {
  check_ok();
  flush_chunk();
  const std::uint64_t at = offset_;
  emit_record(a);
  attachment_indexes_.push_back(
      AttachmentIndex{at, offset_ - at, a.log_time, a.create_time, a.data.size(), a.name, a.media_type});
  ++stats_.attachment_count;
}

void Writer::flush_chunk() {
  if (chunk_.empty()) return;
  const std::uint32_t crc = crc32(chunk_);
  std::span<const std::uint8_t> stored = chunk_;
  if (options_.compression == Compression::Zstd) {
    if (!zstd_) zstd_ = std::make_unique<ZstdCompressor>(options_.zstd_level);
    zstd_->compress(chunk_, compressed_);
    stored = compressed_;
  }
  const std::string compression = to_string(options_.compression);

  // The Chunk record's fields up to its records, then the records themselves: the payload is not copied again.
  Bytes head;
  head.reserve(kRecordPrefix + 8 * 3 + 4 + 4 + compression.size() + 8);
  auto put = [&head](std::uint64_t v, int n) {
    for (int i = 0; i < n; ++i) head.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
  };
  const std::uint64_t body = 8 + 8 + 8 + 4 + 4 + compression.size() + 8 + stored.size();
  head.push_back(static_cast<std::uint8_t>(Opcode::Chunk));
  put(body, 8);
  put(chunk_start_, 8);
  put(chunk_end_, 8);
  put(chunk_.size(), 8);
  put(crc, 4);
  put(compression.size(), 4);
  head.insert(head.end(), compression.begin(), compression.end());
  put(stored.size(), 8);

  ChunkIndex ci;
  ci.message_start_time = chunk_start_;
  ci.message_end_time = chunk_end_;
  ci.chunk_start_offset = offset_;
  ci.chunk_length = kRecordPrefix + body;
  ci.compression = compression;
  ci.compressed_size = stored.size();
  ci.uncompressed_size = chunk_.size();
  emit(head);
  emit(stored);

  // One message index per channel, in log-time order (stable: equal times keep the order they were written).
  const std::uint64_t index_start = offset_;
  for (auto& [id, index] : chunk_indexes_by_channel_) {
    std::stable_sort(index.records.begin(), index.records.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    ci.message_index_offsets[id] = offset_;
    emit_record(index);
  }
  ci.message_index_length = offset_ - index_start;
  chunk_indexes_.push_back(std::move(ci));
  ++stats_.chunk_count;
  chunk_.clear();
  chunk_indexes_by_channel_.clear();
}

void Writer::close() {
  if (closed_) return;
  if (!failure_.empty()) throw McapError(failure_);
  flush_chunk();
  emit_record(DataEnd{data_crc_});
  in_data_section_ = false;

  // The summary: each group of records once, remembered for its summary offset record.
  const std::uint64_t summary_start = offset_;
  Bytes summary;
  std::vector<SummaryOffset> groups;
  auto group = [&](Opcode op, auto&& write_all) {
    const std::size_t at = summary.size();
    write_all();
    if (summary.size() > at)
      groups.push_back(SummaryOffset{static_cast<std::uint8_t>(op), summary_start + at, summary.size() - at});
  };
  group(Opcode::Schema, [&] {
    for (const auto& [id, s] : schemas_) append_record(summary, s);
  });
  group(Opcode::Channel, [&] {
    for (const auto& [id, c] : channels_) append_record(summary, c);
  });
  group(Opcode::Statistics, [&] { append_record(summary, stats_); });
  group(Opcode::MetadataIndex, [&] {
    for (const auto& m : metadata_indexes_) append_record(summary, m);
  });
  group(Opcode::AttachmentIndex, [&] {
    for (const auto& a : attachment_indexes_) append_record(summary, a);
  });
  group(Opcode::ChunkIndex, [&] {
    for (const auto& c : chunk_indexes_) append_record(summary, c);
  });
  const std::uint64_t summary_offset_start = summary_start + summary.size();
  for (const auto& g : groups) append_record(summary, g);

  // The summary CRC covers the summary up to and including the footer's summary_offset_start field.
  Footer footer{summary_start, summary_offset_start, 0};
  Bytes footer_bytes;
  append_record(footer_bytes, footer);
  std::uint32_t crc = crc32(summary);
  crc = crc32_update(crc, std::span(footer_bytes).first(footer_bytes.size() - 4));
  footer.summary_crc = crc;
  footer_bytes.clear();
  append_record(footer_bytes, footer);
  summary.insert(summary.end(), footer_bytes.begin(), footer_bytes.end());
  summary.insert(summary.end(), kMagic.begin(), kMagic.end());
  emit(summary);
  try {
    sink_.flush();
  } catch (const McapError& e) {
    failure_ = e.what();
    throw;
  }
  closed_ = true;
}

}  // namespace fsd::mcap
