#include "daemon/telemetry/run_metrics.hpp"

#include <string>

namespace fsd {

namespace {

constexpr const char* kLatency = "fsd_stage_latency_seconds";
constexpr const char* kLatencyHelp =
    "Wall time of each stage of the control loop: perception, planning, control, and end_to_end from the start of "
    "perception to the command handed to the VCU link (quantiles over the latest 1024)";
constexpr const char* kAsHelp = "AS state of the VCU: 0 Off, 1 Ready, 2 Driving, 3 Emergency, 4 Finished";

}  // namespace

RunMetrics::RunMetrics(web::Metrics& m)
    : registry_(m),
      perception_(m.summary(kLatency, kLatencyHelp, {{"stage", "perception"}})),
      planning_(m.summary(kLatency, kLatencyHelp, {{"stage", "planning"}})),
      planning_cpu_(m.summary("fsd_planning_cpu_seconds",
                              "CPU time of each real-time plan (the planner's budget is about this; its wall time "
                              "also counts the time the thread waited for a core)")),
      control_(m.summary(kLatency, kLatencyHelp, {{"stage", "control"}})),
      end_to_end_(m.summary(kLatency, kLatencyHelp, {{"stage", "end_to_end"}})),
      period_(m.summary("fsd_control_period_seconds", "Wall time between the starts of consecutive control cycles")),
      cycles_(m.counter("fsd_control_cycles_total", "Control cycles run")),
      plans_(m.counter("fsd_plans_total", "Real-time plans made")),
      plans_one_boundary_(m.counter("fsd_plans_one_boundary_total",
                                    "Plans that saw one boundary only and ran half a lane width inside it")),
      plans_colour_blind_(m.counter("fsd_plans_colour_blind_total",
                                    "Plans that ignored cone colours contradicting the geometry (colour-blind)")),
      plans_cut_short_(
          m.counter("fsd_plans_cut_short_total", "Plans that end before a place the body would come too near a cone")),
      late_plans_(m.counter("fsd_late_plans_total",
                            "Plans whose CPU time exceeded control.planner.time_budget (a warning: the plan is used)")),
      rate_(m.gauge("fsd_control_loop_rate_hz", "Control cycles per second of wall time, over the last second")),
      as_state_(m.gauge("fsd_as_state", kAsHelp)),
      laps_(m.gauge("fsd_laps_completed", "Laps completed in this run")),
      cones_hit_(m.gauge("fsd_cones_hit", "Cones knocked over in this run (simulator truth; -1 when unknown)")),
      sim_time_(m.gauge("fsd_run_time_seconds", "The run's clock (simulated time in sim runs)")) {
  for (int i = 0; i < 5; ++i) {
    const std::string name(to_string(static_cast<AsState>(i)));
    as_active_[i] =
        &m.gauge("fsd_as_state_active", "1 for the AS state the VCU is in, 0 for the others", {{"state", name}});
  }
  cones_hit_.set(-1);
}

void RunMetrics::on_cycle_start() {
  const auto now = clock::now();
  if (last_start_ != clock::time_point{}) period_.observe(std::chrono::duration<double>(now - last_start_).count());
  last_start_ = now;
}

void RunMetrics::on_cycle(const CycleFigures& f) {
  const auto now = clock::now();
  if (window_start_ == clock::time_point{}) window_start_ = now;
  ++window_cycles_;
  const double window = std::chrono::duration<double>(now - window_start_).count();
  if (window >= 1.0) {
    rate_.set(static_cast<double>(window_cycles_ - 1) / window);
    window_start_ = now;
    window_cycles_ = 1;
  }
  cycles_.inc();
  if (f.perception_s >= 0) perception_.observe(f.perception_s);
  if (f.planning_s >= 0) planning_.observe(f.planning_s);
  if (f.planning_cpu_s >= 0) planning_cpu_.observe(f.planning_cpu_s);
  if (f.late_plan) late_plans_.inc();
  if (f.planned) {
    plans_.inc();
    if (f.plan_one_boundary) plans_one_boundary_.inc();
    if (f.plan_colour_blind) plans_colour_blind_.inc();
    if (f.plan_cut_short) plans_cut_short_.inc();
  }
  if (f.control_s >= 0) control_.observe(f.control_s);
  if (f.end_to_end_s >= 0) end_to_end_.observe(f.end_to_end_s);
  const int as = static_cast<int>(f.as_state);
  as_state_.set(as);
  for (int i = 0; i < 5; ++i) as_active_[i]->set(i == as ? 1.0 : 0.0);
  laps_.set(f.laps);
  cones_hit_.set(f.cones_hit);
  sim_time_.set(f.t);
}

}  // namespace fsd
