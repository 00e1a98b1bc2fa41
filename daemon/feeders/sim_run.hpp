#pragma once
// `fsd run --sim`: the virtual car as one of the Stack's feeders (daemon/stack/stack.hpp). One thread at the control
// period: the car advances and its sensors hand their wire-format bytes straight to Stack::feed (VLP-16 packets,
// NMEA, camera JPEGs, VCU status), the simulator's truth follows as truth frames (state, standing cones, the ideal
// detector's scan tick), the VCU Command due is sent to the car, and the Stack steps. The scorecard measures the
// run against the truth. Headless runs advance simulated time as fast as the CPU allows (deterministic, the lap-2
// build and the loop closure's solve inside the step; --workers puts them on the Stack's threads); otherwise the
// loop is paced in real time, those jobs run on the Stack's workers and the dashboard is served.
#include <atomic>
#include <functional>
#include <memory>

#include <nlohmann/json_fwd.hpp>

#include "common/config.hpp"
#include "daemon/cli/run_options.hpp"
#include "daemon/scoring/scorecard.hpp"

namespace fsd {

class Telemetry;
class RunMetrics;
class ParamRegistry;
class Stack;

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
  const Stack& stack() const;  // after run(): the map, the start pose
  void set_params(ParamRegistry* params);
  // Called by the loop's thread after each cycle (the service's watchdog, daemon/service/service_notifier.hpp).
  void set_loop_hook(std::function<void()> hook);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace fsd
