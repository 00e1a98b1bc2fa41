#pragma once
// A Chunk record's content, checked and parsed whole: the linear reader and the summary reader both take every
// record of a chunk or none of it, so a damaged chunk is never read as data.
#include <string>
#include <vector>

#include "common/mcap/compression.hpp"
#include "common/mcap/reader_options.hpp"
#include "common/mcap/records.hpp"

namespace fsd::mcap {

class ChunkDecoder {
 public:
  // The records of `chunk` in order into `out` (cleared first); "" on success, else what is wrong, and whether
  // it was the CRC (`*crc_mismatch`).
  std::string decode(const Chunk& chunk, const ReaderOptions& options, std::vector<Record>& out, bool* crc_mismatch);

 private:
  ChunkDecompressor decompressor_;
  Bytes records_;
};

}  // namespace fsd::mcap
