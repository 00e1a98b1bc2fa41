#pragma once
// What a recording holds, for `fsd mcap info`: found by a linear read of the whole file, so it works on files cut
// off mid-write and finds every damaged chunk; the summary is read too and its presence reported.
#include <cstdint>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "common/mcap/reader_options.hpp"
#include "common/mcap/records.hpp"

namespace fsd::mcap {

struct ChannelInfo {
  std::uint16_t id = 0;
  std::string topic;
  std::string message_encoding;
  std::string schema_name;  // "" when schema-less
  std::uint64_t messages = 0;
};

struct AttachmentInfo {
  std::string name;
  std::string media_type;
  std::uint64_t size = 0;
  Timestamp log_time = 0;
};

struct FileInfo {
  std::uint64_t file_size = 0;
  Header header;
  std::uint64_t messages = 0;
  std::optional<Timestamp> start_time, end_time;  // of the messages read (log time)
  std::vector<ChannelInfo> channels;              // by id
  std::uint64_t chunks = 0;                       // intact
  std::uint64_t chunks_damaged = 0;
  std::map<std::string, std::uint64_t> chunk_compressions;  // "" is none
  std::vector<Metadata> metadata;
  std::vector<AttachmentInfo> attachments;
  bool summary_present = false;
  std::string summary_problem;  // why it is absent
  bool complete = false;        // footer and closing magic read
  std::optional<std::uint64_t> truncated_at;
  std::vector<Issue> issues;
};

// Throws McapError when `file` is not MCAP at all (check_magic). Never strict.
FileInfo inspect(std::span<const std::uint8_t> file);

}  // namespace fsd::mcap
