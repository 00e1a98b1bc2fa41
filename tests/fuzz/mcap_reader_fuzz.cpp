// libFuzzer target for the MCAP readers (common/mcap) on arbitrary bytes: the linear reader, the summary reader
// (footer, summary, chunk indexes, and its fallback to the linear scan), inspect() and recover(); and the
// replayer's reader of fsd recordings (daemon/recording_reader: metadata, cycle markers, commands, the run's
// metadata) on the same bytes.
// Invariants checked beyond "no crash, no sanitizer report": the only exception is McapError at the magic check;
// a cut-off point lies inside the input; and what recover() writes is a whole, undamaged file that holds exactly
// the messages it says it kept.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <span>

#include "common/mcap/fsd_profile.hpp"
#include "common/mcap/inspect.hpp"
#include "common/mcap/linear_reader.hpp"
#include "common/mcap/recover.hpp"
#include "common/mcap/summary_reader.hpp"
#include "daemon/recording/recording_reader.hpp"

namespace {

using namespace fsd::mcap;

void require(bool ok) {
  if (!ok) std::abort();
}

// The replayer's path: a file it refuses throws RecordingError; one it takes yields events whose frames never
// outnumber the messages the linear reader found.
void replay_path(std::span<const std::uint8_t> in, std::uint64_t messages, const ReaderOptions& options) {
  try {
    fsd::RecordingReader rec(in, options);
    if (const auto* run = rec.metadata(kRunMetadata)) {
      try {
        (void)fsd::recorded_run_from_metadata(*run);
      } catch (const std::invalid_argument&) {}
    }
    std::uint64_t events = 0;
    while (auto e = rec.next()) {
      ++events;
      if (e->kind == fsd::RecordingEvent::Kind::Command) require(fsd::decode_command(e->bytes).has_value());
    }
    const auto& c = rec.counters();
    require(c.frames + c.cycles + c.commands == events);
    require(events <= messages);
  } catch (const fsd::RecordingError&) {}
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::span<const std::uint8_t> in(data, size);
  try {
    check_magic(in);
  } catch (const McapError&) {
    return 0;
  }
  ReaderOptions options;
  options.max_chunk_size = 1 << 22;  // keeps a lying size field from costing the fuzzer's memory budget

  LinearReader linear(in, options);
  std::uint64_t messages = 0;
  while (auto r = linear.next()) messages += std::holds_alternative<Message>(r->record);
  if (linear.truncated_at()) require(*linear.truncated_at() <= size && !linear.complete());
  replay_path(in, messages, options);

  SummaryReader summary(in, options);
  std::uint64_t via_summary = 0;
  summary.for_each_message([&](const Message&, const Channel&) { ++via_summary; });
  if (!summary.indexed()) require(via_summary <= messages);

  const FileInfo info = inspect(in);
  require(info.file_size == size);

  BufferSink out;
  RecoverReport report;
  WriterOptions rewrite;
  rewrite.compression = Compression::None;  // our writer's zstd path is not what is fuzzed here
  rewrite.chunk_size = 4096;
  try {
    report = recover(in, out, rewrite, options);
  } catch (const NothingToRecover&) {
    return 0;
  }
  ReaderOptions strict = options;
  strict.strict = true;
  LinearReader again(out.data, strict);
  std::uint64_t kept = 0;
  while (auto r = again.next()) kept += std::holds_alternative<Message>(r->record);
  require(again.complete() && again.issues().empty() && kept == report.messages);
  SummaryReader indexed(out.data, strict);
  require(indexed.has_summary());
  std::uint64_t kept_indexed = 0;
  indexed.for_each_message([&](const Message&, const Channel&) { ++kept_indexed; });
  require(kept_indexed == report.messages);
  return 0;
}
