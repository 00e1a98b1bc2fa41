#include "common/mcap/chunk_decoder.hpp"

#include <cstdio>

#include "common/mcap/codec.hpp"
#include "common/mcap/crc32.hpp"

namespace fsd::mcap {

std::string ChunkDecoder::decode(const Chunk& chunk, const ReaderOptions& options, std::vector<Record>& out,
                                 bool* crc_mismatch) {
  out.clear();
  *crc_mismatch = false;
  if (chunk.uncompressed_size > options.max_chunk_size)
    return "uncompressed size " + std::to_string(chunk.uncompressed_size) + " bytes is over the limit of " +
           std::to_string(options.max_chunk_size);
  std::string err = decompressor_.decompress(chunk.compression, chunk.records, chunk.uncompressed_size, records_);
  if (!err.empty()) return err;
  if (options.verify_crcs && chunk.uncompressed_crc != 0) {
    const std::uint32_t crc = crc32(records_);
    if (crc != chunk.uncompressed_crc) {
      *crc_mismatch = true;
      char buf[96];
      std::snprintf(buf, sizeof buf, "CRC mismatch (stored 0x%08x, records give 0x%08x)", chunk.uncompressed_crc, crc);
      return buf;
    }
  }
  std::size_t pos = 0;
  const std::size_t n = records_.size();
  while (pos < n) {
    if (n - pos < kRecordPrefix) return "a record at chunk offset " + std::to_string(pos) + " is cut off";
    const std::uint8_t op = records_[pos];
    const std::uint64_t len = load_u64(records_.data() + pos + 1);
    if (len > n - pos - kRecordPrefix) return "a record at chunk offset " + std::to_string(pos) + " is cut off";
    const std::span<const std::uint8_t> body(records_.data() + pos + kRecordPrefix, static_cast<std::size_t>(len));
    try {
      // A chunk holds schemas, channels and messages; anything else in one is skipped like an unknown opcode.
      const bool allowed = op == static_cast<std::uint8_t>(Opcode::Schema) ||
                           op == static_cast<std::uint8_t>(Opcode::Channel) ||
                           op == static_cast<std::uint8_t>(Opcode::Message);
      if (allowed) out.push_back(std::move(*parse_record(op, body)));
    } catch (const FormatError& e) {
      out.clear();
      return std::string("at chunk offset ") + std::to_string(pos) + ": " + e.what();
    }
    pos += kRecordPrefix + static_cast<std::size_t>(len);
  }
  return "";
}

}  // namespace fsd::mcap
