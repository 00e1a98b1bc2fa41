#include "daemon/feeders/sim_faults.hpp"

#include <algorithm>
#include <cmath>

#include <nlohmann/json.hpp>

#include "daemon/scoring/scorecard.hpp"

namespace fsd {

namespace {
constexpr double kPerceptionPeriod = 0.1;  // s: one LiDAR revolution (truth perception without the LiDAR model)
constexpr double kBefore = 0.5;            // s of truth kept before a window opens
constexpr double kAfter = 3.0;             // s recorded after it closes
constexpr double kMaxWindow = 15.0;        // s of a window recorded at most (long or open-ended ones)
constexpr double kStandstill = 0.05;       // m/s: the VCU stand-in's standstill speed
}  // namespace

SimFaults::SimFaults(sim::VirtualCar& car, bool lidar_simulated) : car_(car), lidar_simulated_(lidar_simulated) {}

bool SimFaults::planner_stalled(Stamp t) const { return car_.faults().active(sim::FaultKind::PlannerStall, t); }

void SimFaults::on_cycle(Stamp t) {
  const sim::FaultSchedule& schedule = car_.faults();
  if (!schedule.any_enabled()) return;

  const sim::VehicleTruth& truth = car_.truth();
  const Sample now{t, truth.speed(), truth.ax, truth.distance};
  for (const sim::FaultKind k : sim::kFaultKinds) {
    Record& r = records_[static_cast<std::size_t>(k)];
    const auto w = schedule.window(k);
    if (!w || r.done || t < w->start) continue;
    if (!r.started) {
      r.started = true;
      for (const Sample& s : recent_)
        if (s.t >= w->start - kBefore) r.trace.push_back(s);
    }
    r.trace.push_back(now);
    if (t >= std::min(w->end, w->start + kMaxWindow) + kAfter) r.done = true;
  }
  recent_.push_back(now);
  while (!recent_.empty() && recent_.front().t < t - kBefore) recent_.pop_front();
}

bool SimFaults::truth_scan_due(Stamp t) {
  // With the VLP-16 simulated its scans drive perception, and a silent one completes none.
  if (lidar_simulated_) return false;
  if (t + 1e-9 < next_perception_) return false;
  next_perception_ += kPerceptionPeriod;
  return !car_.faults().active(sim::FaultKind::Lidar, t);
}

nlohmann::json SimFaults::report() const {
  using nlohmann::json;
  json out = json::array();
  const sim::FaultSchedule& schedule = car_.faults();
  for (const sim::FaultKind k : sim::kFaultKinds) {
    const sim::FaultTrigger& tr = schedule.config().trigger(k);
    if (!tr.enabled()) continue;
    const Record& r = records_[static_cast<std::size_t>(k)];
    json j = {{"fault", std::string(sim::to_string(k))}, {"lap", tr.lap}, {"at_s", tr.at_s}};
    if (k == sim::FaultKind::Gnss) j["mode"] = schedule.config().gnss.mode;
    const auto w = schedule.window(k);
    // A window that never opened (the run ended first, or its lap was never reached) has null times.
    j["start_s"] = w && r.started ? json(w->start) : json(nullptr);
    j["end_s"] = w && r.started && std::isfinite(w->end) ? json(w->end) : json(nullptr);
    j["speed_at_start_m_s"] = nullptr;
    j["stopped_at_s"] = nullptr;
    j["stop_distance_m"] = nullptr;
    json trace = {{"t_s", json::array()}, {"speed_m_s", json::array()}, {"ax_m_s2", json::array()}};
    if (w && r.started) {
      std::optional<Sample> at_start;
      for (const Sample& s : r.trace) {
        trace["t_s"].push_back(milli(s.t));
        trace["speed_m_s"].push_back(milli(s.speed));
        trace["ax_m_s2"].push_back(milli(s.ax));
        if (s.t < w->start) continue;
        if (!at_start) {
          at_start = s;
          j["speed_at_start_m_s"] = s.speed;
        }
        if (j["stopped_at_s"].is_null() && s.speed < kStandstill) {
          j["stopped_at_s"] = s.t;
          j["stop_distance_m"] = s.distance - at_start->distance;
        }
      }
      json as = json::array();
      for (const auto& tr_as : car_.vcu().transitions())
        if (tr_as.t >= w->start - kBefore)
          as.push_back({{"t", tr_as.t}, {"to", std::string(to_string(tr_as.to))}, {"why", tr_as.why}});
      j["as_transitions"] = as;
    }
    j["trace"] = trace;
    out.push_back(j);
  }
  return out;
}

}  // namespace fsd
