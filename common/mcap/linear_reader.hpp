#pragma once
// The streaming (linear) reader: every record of a file in order, from the header to the footer, with each chunk's
// records in place of the chunk. It never throws away what it has read: a file cut off mid-write yields every
// complete record and chunk, then truncated_at() says where it ends; a chunk that fails its CRC or does not
// decompress is reported with its offset and skipped (in strict mode, refused). Unknown opcodes and a newer
// writer's extra bytes at the end of known records are skipped, as the specification says.
#include <cstdint>
#include <map>
#include <optional>
#include <span>
#include <vector>

#include "common/mcap/chunk_decoder.hpp"
#include "common/mcap/reader_options.hpp"
#include "common/mcap/records.hpp"

namespace fsd::mcap {

struct RecordAt {
  Record record;
  std::uint64_t offset = 0;  // of the record in the file, or of the chunk that holds it
  bool in_chunk = false;
};

// Throws McapError unless `file` starts with the MCAP magic of major version 0: "empty file", "not an MCAP
// file ...", "MCAP format version N is newer ...".
void check_magic(std::span<const std::uint8_t> file);

class LinearReader {
 public:
  // `file` must outlive the reader. Throws McapError as check_magic does.
  explicit LinearReader(std::span<const std::uint8_t> file, ReaderOptions options = {});

  // The next record; nullopt at the footer or where the file is cut off. Strict mode: throws McapError at the
  // first damaged chunk or record (and at a data section CRC mismatch).
  std::optional<RecordAt> next();

  const std::vector<Issue>& issues() const { return issues_; }
  bool complete() const { return complete_; }  // footer and closing magic read
  std::optional<std::uint64_t> truncated_at() const { return truncated_at_; }
  std::uint64_t chunks_read() const { return chunks_read_; }        // intact chunks
  std::uint64_t chunks_skipped() const { return chunks_skipped_; }  // damaged ones
  std::uint64_t offset() const { return pos_; }                     // of the next record outside chunks
  // Chunks seen (intact or not) by compression ("" is none).
  const std::map<std::string, std::uint64_t>& chunk_compressions() const { return compressions_; }

 private:
  void report(Issue::Kind kind, std::uint64_t offset, std::string what);
  void truncated(std::uint64_t at, const std::string& why);
  bool open_chunk(const Chunk& chunk, std::uint64_t at);

  std::span<const std::uint8_t> file_;
  ReaderOptions options_;
  std::size_t pos_ = 0;
  bool done_ = false;
  bool complete_ = false;
  bool data_end_seen_ = false;
  std::uint32_t data_crc_ = 0;
  std::optional<std::uint64_t> truncated_at_;
  std::vector<Issue> issues_;
  std::uint64_t chunks_read_ = 0, chunks_skipped_ = 0;
  std::map<std::string, std::uint64_t> compressions_;

  ChunkDecoder decoder_;
  std::vector<Record> chunk_records_;
  std::size_t chunk_next_ = 0;
  std::uint64_t chunk_offset_ = 0;
};

}  // namespace fsd::mcap
