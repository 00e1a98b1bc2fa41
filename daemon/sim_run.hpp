#pragma once
// `fsd run --sim`: the full stack driving the virtual car in-process. The car's sensors emit the real wire
// formats, handed straight to the real decoders (VLP-16 scan builder, NMEA driver, VCU session); perception and
// localization run from the configured source; the autopilot drives; the scorecard measures against the truth.
// Headless runs advance a LockstepClock as fast as the CPU allows (deterministic); otherwise the loop is paced
// in real time and the dashboard is served.
#include <atomic>
#include <functional>
#include <memory>

#include <nlohmann/json_fwd.hpp>

#include "common/config.hpp"
#include "daemon/run_options.hpp"
#include "daemon/scorecard.hpp"

namespace fsd {

class Telemetry;
class RunMetrics;
class ParamRegistry;

// Per-cycle view of the run for the dashboard and logs.
struct SimRunHooks {
  std::function<void(Stamp)> on_cycle;  // after each control cycle (telemetry publishing)
};

class SimRun {
 public:
  SimRun(const Config& config, const RunOptions& options);
  ~SimRun();
  // Runs until the mission is over (with --until-finished), max_sim_time, or `stop` becomes true.
  // Returns the exit status: 0 mission done (or stopped by the user), 1 mission failed.
  int run(const std::atomic<bool>& stop);
  const Scorecard& scorecard() const;
  void set_telemetry(Telemetry* telemetry);
  // Per-cycle figures for /metrics (latencies, loop rate, AS state); wait-free on the loop's side.
  void set_metrics(RunMetrics* metrics);
  // Live tuning: changes of the registry's control.* parameters reach the autopilot at the next cycle.
  void set_params(ParamRegistry* params);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace fsd
