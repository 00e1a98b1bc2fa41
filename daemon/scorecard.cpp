#include "daemon/scorecard.hpp"

#include <cmath>

#include <nlohmann/json.hpp>

namespace fsd {

Scorecard::Scorecard(const Track& track, Mission mission, int laps_to_finish, double stop_zone_m, int seed)
    : track_(track),
      mission_(mission),
      laps_to_finish_(laps_to_finish),
      stop_zone_m_(stop_zone_m),
      seed_(seed),
      ref_(track),
      gates_(track) {}

void Scorecard::on_truth(const sim::VehicleTruth& truth) {
  sim_time_ = truth.t;
  const Vec2 pos = truth.pose.position();
  if (!last_) {
    // A car that starts just past a timing line (some FSDS layouts) has begun its first lap at the start, as the
    // stack's lap counter also counts it; otherwise lap 1 begins at the first crossing.
    for (std::size_t g = 0; g < gates_.gates().size(); ++g) {
      const double past = gates_.past(g, pos);
      const Vec2 lat(-gates_.gates()[g].forward.y(), gates_.gates()[g].forward.x());
      if (past > 0.0 && past < 10.0 && std::fabs((pos - gates_.gates()[g].centre).dot(lat)) <= gates_.gates()[g].half_width)
        lap_start_ = truth.t;
    }
  } else {
    if (const auto g = gates_.crossed(last_->pose.position(), pos); g && !finished_) {
      // Interpolate the crossing time for lap times better than one step.
      const double da = gates_.past(*g, last_->pose.position()), db = gates_.past(*g, pos);
      const Stamp t = last_->t + (truth.t - last_->t) * (da / (da - db));
      if (lap_start_) {
        LapRecord lap;
        lap.lap = static_cast<int>(laps_.size()) + 1;
        lap.time_s = t - *lap_start_;
        lap.cte_rms_m = cte_n_ ? std::sqrt(cte_sq_ / static_cast<double>(cte_n_)) : 0.0;
        lap.cte_max_m = cte_max_;
        lap.v_max_m_s = v_max_;
        laps_.push_back(lap);
        if (static_cast<int>(laps_.size()) >= laps_to_finish_) {
          finished_ = true;
          finish_gate_ = *g;
        }
      }
      lap_start_ = t;
      cte_sq_ = cte_max_ = v_max_ = 0;
      cte_n_ = 0;
    }
  }
  if (lap_start_ && !finished_) {
    const double cte = ref_.distance(pos);
    cte_sq_ += cte * cte;
    cte_max_ = std::max(cte_max_, cte);
    ++cte_n_;
    v_max_ = std::max(v_max_, truth.speed());
  }
  if (finished_ && !stopped_after_finish_ && !left_stop_zone_) {
    const double past = gates_.past(finish_gate_, pos);
    if (past > stop_zone_m_ || ref_.distance(pos) > 4.0) left_stop_zone_ = true;
    else if (truth.speed() < 0.05) stopped_after_finish_ = true;
  }
  last_ = truth;
}

void Scorecard::set_section(const std::string& key, const nlohmann::json& value) {
  sections_[key] = std::make_shared<const nlohmann::json>(value);
}

bool Scorecard::mission_succeeded() const {
  return finished_ && stopped_after_finish_ && as_state_ == AsState::Finished && cones_hit_ == 0;
}

nlohmann::json Scorecard::to_json() const {
  using nlohmann::json;
  json j;
  j["track"] = track_.name;
  j["mission"] = std::string(to_string(mission_));
  j["seed"] = seed_;
  j["finished"] = finished_;
  j["stopped_after_finish"] = stopped_after_finish_;
  j["as_state"] = std::string(to_string(as_state_));
  j["sim_time_s"] = sim_time_;
  j["wall_time_s"] = wall_time_s_;
  j["cones_hit"] = cones_hit_;
  j["laps"] = json::array();
  for (const auto& l : laps_)
    j["laps"].push_back({{"lap", l.lap},
                         {"time_s", l.time_s},
                         {"cte_rms_m", l.cte_rms_m},
                         {"cte_max_m", l.cte_max_m},
                         {"v_max_m_s", l.v_max_m_s}});
  j["vehicle"] = {{"mu", limits_.mu},
                  {"a_accel_max", limits_.a_accel_max},
                  {"a_brake_max", limits_.a_brake_max},
                  {"v_max", limits_.v_max}};
  json lat = json::object();
  for (const auto& [stage, s] : latency_)
    lat[stage] = {{"p50", s.quantile(0.5) * 1e3}, {"p99", s.quantile(0.99) * 1e3}, {"max", s.max() * 1e3},
                  {"n", s.count()}};
  j["latency_ms"] = lat;
  j["faults"] = json::array();
  for (const auto& f : faults_)
    j["faults"].push_back({{"t", f.t}, {"source", f.source}, {"what", f.what}, {"action", f.action}});
  for (const auto& [k, v] : sections_) j[k] = *v;
  return j;
}

}  // namespace fsd
