#pragma once
// The run's figures on the dashboard server's /metrics (Prometheus): per-stage latency, the control loop's rate
// and period, AS state, laps, cones hit. Everything is registered in the constructor (which takes the registry's
// lock); the per-cycle update is wait-free (relaxed atomics), so the control loop never waits on a scrape.
#include <chrono>
#include <cstdint>

#include "common/types.hpp"
#include "control/autopilot.hpp"
#include "web/metrics.hpp"

namespace fsd {

// What one control cycle measured; a negative latency means "this stage did not run in this cycle".
struct CycleFigures {
  Stamp t = 0;                     // run clock
  double perception_s = -1;        // wall time of the perception stage (sensor frame → cone map update)
  double planning_s = -1;          // wall time of a new plan
  double planning_cpu_s = -1;      // its CPU time (what the budget is about: the wall time includes waiting for a core)
  bool late_plan = false;          // that CPU time exceeded control.planner.time_budget (a warning, the plan is used)
  double control_s = -1;           // wall time of the path follower and supervisor
  bool planned = false;            // a real-time plan ran; and what it had to do:
  bool plan_one_boundary = false;  //   only one boundary seen
  bool plan_colour_blind = false;  //   colours contradicted the geometry
  bool plan_cut_short = false;     //   ending before a place the body would come too near a cone
  double end_to_end_s = -1;        // from the start of perception to the command handed to the VCU link
  AsState as_state = AsState::Off;
  int laps = 0;
  int cones_hit = -1;  // -1: unknown (not a simulated run)
};

class RunMetrics {
 public:
  explicit RunMetrics(web::Metrics& metrics);
  // Called by the feeder's control loop as each cycle starts (it woke up for it): the loop's period.
  void on_cycle_start();
  // Called by the control loop once per cycle, at its end. Wait-free.
  void on_cycle(const CycleFigures& f);
  // The registry, for the run's other parts that count something (the recorder).
  web::Metrics& registry() { return registry_; }

 private:
  using clock = std::chrono::steady_clock;
  web::Metrics& registry_;
  web::Summary &perception_, &planning_, &planning_cpu_, &control_, &end_to_end_, &period_;
  web::Counter &cycles_, &plans_, &plans_one_boundary_, &plans_colour_blind_, &plans_cut_short_, &late_plans_;
  web::Gauge &rate_, &as_state_, &laps_, &cones_hit_, &sim_time_;
  web::Gauge* as_active_[5];
  clock::time_point last_start_{}, window_start_{};
  std::uint64_t window_cycles_ = 0;
};

}  // namespace fsd
