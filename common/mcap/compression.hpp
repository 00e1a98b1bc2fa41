#pragma once
// Chunk compression: "" (none) and "zstd", the two this library writes and reads. lz4, the specification's third,
// is reported as unsupported by the reader.
#include <cstdint>
#include <memory>
#include <span>
#include <string>

#include "common/mcap/records.hpp"

namespace fsd::mcap {

enum class Compression { None, Zstd };
const char* to_string(Compression c);  // the Chunk record's compression string: "" or "zstd"

// One zstd context reused for every chunk (allocating one per chunk would cost more than small chunks' work).
class ZstdCompressor {
 public:
  explicit ZstdCompressor(int level);
  ~ZstdCompressor();
  ZstdCompressor(const ZstdCompressor&) = delete;
  ZstdCompressor& operator=(const ZstdCompressor&) = delete;
  void compress(std::span<const std::uint8_t> in, Bytes& out);  // replaces out's content

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Decompresses chunks with one reused zstd context.
class ChunkDecompressor {
 public:
  ChunkDecompressor();
  ~ChunkDecompressor();
  ChunkDecompressor(const ChunkDecompressor&) = delete;
  ChunkDecompressor& operator=(const ChunkDecompressor&) = delete;
  // A chunk's records into `out`, which must come out exactly `uncompressed_size` bytes long. Returns "" on
  // success, else what is wrong (unknown compression, damaged data, wrong size).
  std::string decompress(const std::string& compression, std::span<const std::uint8_t> in,
                         std::uint64_t uncompressed_size, Bytes& out);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace fsd::mcap
