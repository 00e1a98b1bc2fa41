#pragma once
// `fsd run --replay FILE`: a recording (daemon/recording/recorder.hpp) as the third of the Stack's feeders. The Stack is
// built from the recorded configuration (a --config file on top overrides keys) and the recorded StackOptions;
// every raw frame is fed in recorded order with its exact receive time, and at each recorded cycle the VCU
// session is ticked as the live feeder did and the Stack steps at the recorded time. The command each step
// computes is compared, bit for bit, with the one recorded: mismatches are counted, the first is logged.
// A recording of a simulated run is scored against its recorded truth with the simulator's scorecard
// (daemon/scoring/sim_scoring.hpp). Headless: as fast as the CPU allows; otherwise paced at --rate x real time with the
// dashboard. A recording made in lockstep (fsd run --sim --headless) replays bit for bit; one made in real time
// built its lap-2 path on a worker thread, so its commands may differ after that build (counted, not an error).
#include <atomic>
#include <memory>

#include <nlohmann/json_fwd.hpp>

#include <spdlog/logger.h>

#include "common/config.hpp"
#include "common/mcap/records.hpp"
#include "daemon/cli/run_options.hpp"

namespace fsd {

class Telemetry;
class RunMetrics;
class ParamRegistry;
class Stack;

// The recorded configuration (fsd.config), then the keys of `config_file` (may be empty) over it. A key this fsd does
// not know (a recording of another version) is left out with a warning; a value it refuses is a ConfigError.
Config replay_config(const mcap::StringMap& recorded, const std::string& config_file, spdlog::logger& log);

class ReplayRun {
 public:
  // Reads the recording's metadata and builds the Stack. Throws mcap::McapError (no MCAP file), RecordingError
  // (not a replayable recording), ConfigError or std::invalid_argument (a bad configuration): exit 2.
  explicit ReplayRun(const RunOptions& options);
  ~ReplayRun();
  ReplayRun(const ReplayRun&) = delete;
  ReplayRun& operator=(const ReplayRun&) = delete;

  // The configuration the Stack runs on (the recorded one with --config on top): the dashboard's.
  const Config& config() const;
  bool simulator() const;  // a recording of a simulated run: the report is its scorecard

  // Plays the whole recording or until `stop`. 0; 1 when a lockstep recording's commands did not replay bit for
  // bit, or with --until-finished when a simulated run's mission failed.
  int run(const std::atomic<bool>& stop);
  // The scorecard (simulated runs) or the car run's summary, with a "replay" section: frames, cycles, commands
  // compared and mismatched, the first mismatch's time, the file's damage.
  nlohmann::json report() const;
  void set_telemetry(Telemetry* telemetry);
  void set_metrics(RunMetrics* metrics);
  const Stack& stack() const;  // after run(): the map, the start pose
  void set_params(ParamRegistry* params);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace fsd
