#pragma once
// Summary-based access: the footer and summary at the end of a file (schemas, channels, statistics, chunk,
// attachment and metadata indexes) read without touching the data section, and messages read chunk by chunk
// through the chunk indexes. When the summary is absent or damaged, or its chunk indexes do not account for the
// file's messages, messages come from a linear scan instead, so a file cut off mid-write still reads.
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "common/mcap/chunk_decoder.hpp"
#include "common/mcap/reader_options.hpp"
#include "common/mcap/records.hpp"

namespace fsd::mcap {

struct Summary {
  Header header;
  Footer footer;
  std::map<std::uint16_t, Schema> schemas;
  std::map<std::uint16_t, Channel> channels;
  std::optional<Statistics> statistics;
  std::vector<ChunkIndex> chunk_indexes;
  std::vector<AttachmentIndex> attachment_indexes;
  std::vector<MetadataIndex> metadata_indexes;
  std::vector<SummaryOffset> summary_offsets;
};

// The summary of `file` (which passed check_magic), or nullopt with the reason in *why: no footer (cut off), no
// summary section, a summary CRC mismatch, a record that does not fit. Never reads the data section beyond the
// header.
std::optional<Summary> read_summary(std::span<const std::uint8_t> file, const ReaderOptions& options, std::string* why);

class SummaryReader {
 public:
  // Throws McapError as check_magic does. `file` must outlive the reader.
  explicit SummaryReader(std::span<const std::uint8_t> file, ReaderOptions options = {});

  bool has_summary() const { return summary_.has_value(); }
  const std::string& summary_problem() const { return summary_problem_; }  // why there is none
  const std::optional<Summary>& summary() const { return summary_; }
  // True when messages are read through the chunk indexes; false when a linear scan stands in.
  bool indexed() const { return indexed_; }

  // Every intact message with its channel, chunk by chunk in order of start time, each chunk's messages in
  // log-time order (stable). Channels come from the summary and the chunks themselves or, for a linear scan, from
  // the file as read; a message whose channel is defined nowhere is skipped. A damaged chunk is an issue and
  // skipped (strict mode: McapError).
  void for_each_message(const std::function<void(const Message&, const Channel&)>& visit);
  const std::vector<Issue>& issues() const { return issues_; }

 private:
  void read_indexed(const std::function<void(const Message&, const Channel&)>& visit);
  void read_linear(const std::function<void(const Message&, const Channel&)>& visit);

  std::span<const std::uint8_t> file_;
  ReaderOptions options_;
  std::optional<Summary> summary_;
  std::string summary_problem_;
  bool indexed_ = false;
  std::vector<Issue> issues_;
  ChunkDecoder decoder_;
};

}  // namespace fsd::mcap
