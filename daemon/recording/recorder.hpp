#pragma once
// `fsd run --record FILE`: a StackTap that records every raw frame the Stack takes, a marker per control cycle and
// the command the cycle computed to MCAP (daemon/recording/recording_format.hpp says what goes where), and beside them the
// derived channels (daemon/recording/derived_channels.hpp: pose, scene, AS status, faults, parameter changes) and the log
// lines, JSON-encoded with the dashboard's schemas for Foxglove Studio. The tap only copies
// into a bounded queue (the control thread never waits on the disk; when the queue is full the oldest item is
// dropped and counted); a thread of the recorder's own writes the files. Files split at record.split_mb, always
// after a whole cycle; each part carries the configuration, the run's metadata and the track, so it replays alone.
// A write error (a full disk) stops the recording with one error line in the log, never the run. close() (or the
// destructor) drains the queue and finishes the file with its summary. The snapshots' JSON is built on the writer
// thread, never on the control thread. Log lines come from any thread through a queue of their own (a burst of
// them never pushes a raw frame out).
#include <atomic>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "common/config.hpp"
#include "common/mcap/records.hpp"
#include "daemon/recording/recording_format.hpp"
#include "daemon/stack/raw_frame.hpp"
#include "web/channels.hpp"
#include "web/log_sink.hpp"

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
  std::uint64_t derived_written = 0;  // JSON messages: derived channels, parameter changes, log lines
  std::uint64_t log_dropped = 0;      // log lines lost to a full log queue (not counted in `dropped`)
  std::uint64_t dropped = 0;          // items lost: the queue was full, or the recording had stopped on an error
  std::uint64_t bytes = 0;            // written to every file so far
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
  web::CarShape car;       // the body drawn on /vehicle/car (the car's description)
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
  bool wants_snapshots() const override { return true; }
  void on_snapshot(const std::shared_ptr<const TelemetrySnapshot>& snapshot) override;
  void on_param(Stamp now, const ParamChange& change) override;
  // A log line from any thread (web::make_log_sink's handler); stamped with the newest cycle's time on the run's
  // clock. Never blocks: when the log queue is full the line is counted in log_dropped.
  void on_log(web::LogLine line);
  // A sink that hands every log line at info and above to on_log (attach it with LogForwarding; detach it before
  // the recorder goes away).
  std::shared_ptr<spdlog::sinks::sink> log_sink();

  // Its counters on /metrics (fsd_record_*), updated by the writer thread; `metrics` must outlive the recorder.
  void set_metrics(web::Metrics& metrics);
  // Metadata written into the last part when it is closed (before close(); the last call per name wins).
  void add_closing_metadata(const std::string& name, mcap::StringMap values);
  // Writes what is queued and finishes the file (summary). Idempotent; later frames are not recorded.
  void close();
  RecorderStats stats() const;  // any thread

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace fsd
