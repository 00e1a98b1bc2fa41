#pragma once
// `fsd mcap recover`: rewrites a file cut off mid-write, or with damaged chunks, into a whole one with a full
// summary. Every intact schema, channel, message (with its ids, times and sequence), metadata record and
// attachment is kept; what could not be read is counted and listed.
#include <cstdint>
#include <span>
#include <vector>

#include "common/mcap/byte_io.hpp"
#include "common/mcap/reader_options.hpp"
#include "common/mcap/writer.hpp"

namespace fsd::mcap {

struct RecoverReport {
  std::uint64_t messages = 0;
  std::uint64_t schemas = 0;
  std::uint64_t channels = 0;
  std::uint64_t metadata = 0;
  std::uint64_t attachments = 0;
  std::uint64_t chunks_read = 0;               // intact chunks of the input
  std::uint64_t chunks_lost = 0;               // damaged chunks skipped
  std::uint64_t messages_without_channel = 0;  // dropped: their channel's record was in a lost part
  std::uint64_t channels_without_schema = 0;   // kept schema-less: their schema's record was lost
  std::uint64_t bytes_lost = 0;                // after the point where the input is cut off
  bool input_complete = false;                 // the input had its footer (it may still have had damaged chunks)
  std::vector<Issue> issues;                   // what the linear read of the input found
};

// The input holds nothing to recover (not even a complete header).
class NothingToRecover : public McapError {
 public:
  using McapError::McapError;
};

// Reads `in` linearly (never strictly) and writes what it holds through a Writer on `out`; the profile of the
// input's header is kept, the library is `options.library`. Throws McapError when `in` is no MCAP file at all
// (check_magic), NothingToRecover when it has not even a complete header, and McapError when `out` fails.
RecoverReport recover(std::span<const std::uint8_t> in, ByteSink& out, WriterOptions options = {},
                      ReaderOptions read = {});  // read.strict is ignored

}  // namespace fsd::mcap
