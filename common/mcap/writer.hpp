#pragma once
// Writes one MCAP file: header, schemas and channels, messages in chunks (zstd or uncompressed, each with the CRC
// of its uncompressed records and followed by one message index per channel), metadata and attachments, then the
// data end (with the data section's CRC), the summary (schemas, channels, statistics, metadata, attachment and
// chunk indexes), summary offsets and the footer (with the summary's CRC). Schemas and channels are written in
// the data section outside chunks, before the first chunk that uses them: a file whose first chunk is damaged
// still says what every channel is.
//
// Nothing here owns a thread or a clock: the caller stamps messages. Splitting a long run into files is the
// caller's (it opens a new Writer); bytes_written() says how far the current file has grown.
#include <cstdint>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "common/mcap/byte_io.hpp"
#include "common/mcap/compression.hpp"
#include "common/mcap/records.hpp"

namespace fsd::mcap {

// "fsd-daemon <version>": the Header's library field of every file this project writes.
std::string library_name();

struct WriterOptions {
  std::string profile = "fsd";           // Header.profile (common/mcap/fsd_profile.hpp: kProfile)
  std::string library = library_name();  // Header.library
  Compression compression = Compression::Zstd;
  std::uint64_t chunk_size = 1 << 20;  // a chunk is closed once its uncompressed records reach this (bytes)
  int zstd_level = 3;                  // zstd's default: 0.9 % of a core at full sensor rate
};

class Writer {
 public:
  // Writes the magic and the header at once. Throws McapError when the sink fails.
  explicit Writer(ByteSink& sink, WriterOptions options = {});
  // Finishes the file as close() does, so a writer dropped without close() still leaves a whole file; errors
  // cannot be reported from here (call close() to see them).
  ~Writer();
  Writer(const Writer&) = delete;
  Writer& operator=(const Writer&) = delete;

  // Registers a schema under the next free id (from 1) and returns the id.
  std::uint16_t add_schema(const std::string& name, const std::string& encoding, std::span<const std::uint8_t> data);
  // Registers a channel under the next free id (from 1); schema_id 0 means schema-less.
  std::uint16_t add_channel(const std::string& topic, const std::string& message_encoding, std::uint16_t schema_id,
                            const StringMap& metadata = {});
  // The same with the caller's ids (a rewrite keeps a file's ids). Throws McapError on an id already taken or,
  // for a channel, an unknown schema id.
  void add_schema(const Schema& schema);
  void add_channel(const Channel& channel);

  // A message on a registered channel; its sequence number is the channel's message count so far.
  void write_message(std::uint16_t channel_id, Timestamp log_time, Timestamp publish_time,
                     std::span<const std::uint8_t> data);
  void write_message(const Message& message);  // with the caller's sequence number
  // Metadata (name and string map) and attachments go in the data section between chunks, indexed in the summary.
  void write_metadata(const std::string& name, const StringMap& values);
  void write_attachment(const Attachment& attachment);

  // Writes the open chunk, the data end, the summary and the footer, and flushes the sink. Idempotent. Throws
  // McapError when the sink fails; the file is then incomplete and later calls throw the same error.
  void close();
  bool closed() const { return closed_; }

  std::uint64_t bytes_written() const { return offset_; }        // handed to the sink so far
  std::uint64_t bytes_pending() const { return chunk_.size(); }  // in the open chunk, uncompressed
  const Statistics& statistics() const { return stats_; }

 private:
  void emit(std::span<const std::uint8_t> bytes);
  void emit_record(const Record& r);
  void check_ok() const;
  void flush_chunk();
  void append_message(std::uint16_t channel_id, std::uint32_t sequence, Timestamp log_time, Timestamp publish_time,
                      std::span<const std::uint8_t> data);

  ByteSink& sink_;
  WriterOptions options_;
  std::unique_ptr<ZstdCompressor> zstd_;  // made with the first zstd chunk
  std::uint64_t offset_ = 0;
  std::uint32_t data_crc_ = 0;  // of every byte before the DataEnd record
  bool in_data_section_ = true;
  bool closed_ = false;
  std::string failure_;  // the sink's error, once it has failed

  std::map<std::uint16_t, Schema> schemas_;
  std::map<std::uint16_t, Channel> channels_;
  std::map<std::uint16_t, std::uint32_t> next_sequence_;

  Bytes chunk_;  // the open chunk's uncompressed records
  Bytes compressed_;
  Timestamp chunk_start_ = 0, chunk_end_ = 0;
  std::map<std::uint16_t, MessageIndex> chunk_indexes_by_channel_;

  Statistics stats_;
  std::vector<ChunkIndex> chunk_indexes_;
  std::vector<MetadataIndex> metadata_indexes_;
  std::vector<AttachmentIndex> attachment_indexes_;
};

}  // namespace fsd::mcap
