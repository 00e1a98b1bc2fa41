#pragma once
// Reads a recording of `fsd run --record` (daemon/recording/recording_format.hpp) for the replayer, in file order, with the
// linear MCAP reader: a file cut off mid-write plays up to its last complete chunk, a chunk that fails its CRC is
// skipped and reported with its offset (issues()). The constructor reads up to the first message: the recording's
// metadata and attachments, refusing a file of a newer recording version. Then next() yields the raw frames, each
// control cycle's marker and the recorded commands, in the order the Stack took them; a cycle's frames are held
// back until its marker and given the exact receive times it lists (frames left after the last marker, or whose
// marker lists another count, keep their nanosecond log times and are counted as inexact).
// Pure: no I/O of its own (the caller maps the file), no threads; every field of untrusted input is checked.
#include <cstdint>
#include <deque>
#include <map>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/mcap/linear_reader.hpp"
#include "daemon/recording/recording_format.hpp"
#include "daemon/stack/raw_frame.hpp"

namespace fsd {

// A file that is MCAP but no replayable recording (a newer version, no fsd.config); what() is a sentence.
class RecordingError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct RecordingEvent {
  enum class Kind { Frame, Cycle, Command } kind = Kind::Frame;
  RawChannel channel = RawChannel::Nmea;  // Frame
  Stamp t = 0;                            // the frame's receive time, the cycle's now, the command's now
  std::vector<std::uint8_t> bytes;        // Frame: the device's bytes; Command: the encoded command
};

struct RecordingReaderCounters {
  std::uint64_t frames = 0, cycles = 0, commands = 0;
  std::uint64_t inexact_frames = 0;  // replayed with their nanosecond time (see above)
  std::uint64_t bad_messages = 0;    // a marker or command that does not decode, a message on an unknown channel
  std::uint64_t other_messages = 0;  // on channels the replay does not use (derived channels)
};

class RecordingReader {
 public:
  // `file` must outlive the reader. Throws mcap::McapError for a file that is no MCAP at all (empty, bad magic,
  // newer format) and RecordingError for a recording this fsd cannot replay.
  explicit RecordingReader(std::span<const std::uint8_t> file, mcap::ReaderOptions options = {});

  // The metadata record `name` (the first of that name), or null.
  const mcap::StringMap* metadata(std::string_view name) const;
  // The attachment `name`'s bytes, or nullopt.
  std::optional<std::string> attachment(std::string_view name) const;

  std::optional<RecordingEvent> next();

  const RecordingReaderCounters& counters() const { return counters_; }
  const std::vector<mcap::Issue>& issues() const { return reader_.issues(); }
  std::optional<std::uint64_t> truncated_at() const { return reader_.truncated_at(); }
  bool complete() const { return reader_.complete(); }

 private:
  enum class Use { Raw, Cycle, Command, Other };
  struct ChannelUse {
    Use use = Use::Other;
    RawChannel raw = RawChannel::Nmea;
  };
  void take(const mcap::Record& r);      // metadata, attachments, channels
  bool take_message(mcap::Message&& m);  // true when events were queued
  void flush_frames(const CycleMarker* marker);

  mcap::LinearReader reader_;
  std::vector<mcap::Metadata> metadata_;
  std::vector<mcap::Attachment> attachments_;
  std::map<std::uint16_t, ChannelUse> channels_;
  std::optional<mcap::Message> first_message_;  // read ahead by the constructor
  std::vector<RecordingEvent> held_;            // frames waiting for their cycle's marker
  std::deque<RecordingEvent> ready_;
  bool done_ = false;
  RecordingReaderCounters counters_;
};

}  // namespace fsd
