#pragma once
// `fsd run --record FILE`: a StackTap that records every raw frame the Stack takes, a marker per control cycle and
// the command the cycle computed to MCAP (daemon/recording_format.hpp says what goes where). The tap only copies
// into a bounded queue (the control thread never waits on the disk; when the queue is full the oldest item is
// dropped and counted); a thread of the recorder's own writes the files. Files split at record.split_mb, always
// after a whole cycle; each part carries the configuration, the run's metadata and the track, so it replays alone.
// A write error (a full disk) stops the recording with one error line in the log, never the run. close() (or the
// destructor) drains the queue and finishes the file with its summary.
#include <atomic>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "common/config.hpp"
#include "common/mcap/records.hpp"
#include "daemon/raw_frame.hpp"
#include "daemon/recording_format.hpp"

namespace fsd {

namespace web {
class Metrics;
}

struct RecordSettings {
  double split_mb = 2048;    // a new file once the current one reaches this (MiB)
  int queue_frames = 16384;  // items (frames, markers, commands) between the control thread and the writer
};
const ConfigSection<RecordSettings>& record_section();

struct RecorderStats {
  std::uint64_t frames_written = 0, cycles_written = 0, commands_written = 0;
  std::uint64_t dropped = 0;  // items lost: the queue was full, or the recording had stopped on an error
  std::uint64_t bytes = 0;    // written to every file so far
  std::uint64_t queue_high_water = 0;
  std::vector<std::string> files;
  std::string error;  // why the recording stopped early; empty when it did not
};
nlohmann::json to_json(const RecorderStats& s);

// What every file of the recording carries besides the messages.
struct RecordingContents {
  nlohmann::json const* config = nullptr;  // the configuration the Stack was built from (Config::as_json)
  RecordedRun run;
  std::string track_file;  // the layout driven (simulator runs), attached as it is on disk
};

// The path of part `part` of a recording: part 0 is `first` itself, then "run-001.mcap", "run-002.mcap", ...
std::string recording_part_path(const std::string& first, int part);

class Recorder final : public StackTap {
 public:
  // Creates the first file at once: throws std::invalid_argument naming the path when it cannot be created.
  // `lossless`: when the queue is full the tap waits for the writer instead of dropping (headless lockstep runs:
  // they have no real time to keep, and a dropped frame would keep the replay from repeating the run).
  Recorder(std::string path, RecordSettings settings, const RecordingContents& contents, bool lossless = false);
  ~Recorder() override;
  Recorder(const Recorder&) = delete;
  Recorder& operator=(const Recorder&) = delete;

  void on_frame(const RawFrame& frame) override;
  void on_cycle(Stamp now) override;
  void on_output(Stamp now, const ControlCommand& command, wire::vcu::AsRequest request) override;

  // Its counters on /metrics (fsd_record_*), updated by the writer thread; `metrics` must outlive the recorder.
  void set_metrics(web::Metrics& metrics);
  // Writes what is queued and finishes the file (summary). Idempotent; later frames are not recorded.
  void close();
  RecorderStats stats() const;  // any thread

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace fsd
