#pragma once
// What the readers report and how strict they are, shared by the linear and the summary reader.
#include <cstdint>
#include <string>

namespace fsd::mcap {

struct ReaderOptions {
  bool strict = false;      // a damaged chunk or record refuses the file (McapError) instead of being skipped
  bool verify_crcs = true;  // chunk, data section and summary CRCs (a stored 0 means "not computed")
  std::uint64_t max_chunk_size = 1ull << 30;  // uncompressed bytes; a chunk claiming more is treated as damaged
};

// Something wrong with a file that did not stop the reading: where it is and what it is. `what` starts with
// "chunk at offset N", "record at offset N" or "truncated at offset N".
struct Issue {
  enum class Kind {
    ChunkCrc,      // a chunk whose records do not match their CRC: skipped
    ChunkDamaged,  // a chunk that cannot be decompressed or whose records do not parse: skipped
    BadRecord,     // a record outside chunks whose fields do not parse: skipped
    DataCrc,       // the data section's CRC does not match
    Truncated,     // the file ends inside a record or before its footer
  };
  Kind kind;
  std::uint64_t offset;  // of the damaged record or chunk, or where the file is cut off
  std::string what;
};
const char* to_string(Issue::Kind k);

}  // namespace fsd::mcap
