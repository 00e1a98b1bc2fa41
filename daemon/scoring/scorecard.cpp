#include "daemon/scoring/scorecard.hpp"

#include <algorithm>
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
      gates_(track) {
  open_ = (mission == Mission::Trackdrive || mission == Mission::Autocross) && !ref_.closed() &&
          ref_.left().size() >= 2 && ref_.right().size() >= 2;
  if (mission == Mission::Skidpad && !gates_.gates().empty()) {
    // The circles' centres lie on the timing line, one driving radius either side of the crossing.
    skidpad_gate_ = gates_.gates().front();
    const Vec2 lat(-skidpad_gate_.forward.y(), skidpad_gate_.forward.x());
    skidpad_centres_ = {skidpad_gate_.centre + kSkidpadRadius * lat, skidpad_gate_.centre - kSkidpadRadius * lat};
  }
  if (open_) {
    laps_to_finish_ = 1;
    // The end line joins the last cone of each boundary; its forward side is the one with the left boundary on
    // the left.
    const Vec2 l = ref_.left().back(), r = ref_.right().back();
    const Vec2 across = l - r;
    end_gate_.centre = 0.5 * (l + r);
    end_gate_.forward = Vec2(across.y(), -across.x()).normalized();
    end_gate_.half_width = 0.5 * across.norm() + 1.0;
  }
}

double Scorecard::centre_distance(const Vec2& p) const {
  if (skidpad_centres_.empty()) return ref_.distance(p);
  // The nearer circle, or the entry/exit axis through the crossing (tangent to both circles there).
  const Vec2 lat(-skidpad_gate_.forward.y(), skidpad_gate_.forward.x());
  double d = std::fabs((p - skidpad_gate_.centre).dot(lat));
  for (const Vec2& c : skidpad_centres_) d = std::min(d, std::fabs((p - c).norm() - kSkidpadRadius));
  return d;
}

namespace {
double past(const sim::Gate& g, const Vec2& p) { return (p - g.centre).dot(g.forward); }

// Crossed forwards between a and b within the gate's width: the fraction of the way, else nullopt.
std::optional<double> crossing(const sim::Gate& g, const Vec2& a, const Vec2& b) {
  const double da = past(g, a), db = past(g, b);
  if (!(da < 0.0 && db >= 0.0)) return std::nullopt;
  const double f = da / (da - db);
  const Vec2 x = a + (b - a) * f;
  const Vec2 lat(-g.forward.y(), g.forward.x());
  if (std::fabs((x - g.centre).dot(lat)) > g.half_width) return std::nullopt;
  return f;
}
}  // namespace

void Scorecard::on_truth(const sim::VehicleTruth& truth) {
  sim_time_ = truth.t;
  const Vec2 pos = truth.pose.position();
  // The gate crossed this step, if any, and when.
  std::optional<sim::Gate> crossed;
  Stamp t_cross = truth.t;
  if (!last_) {
    // A car that starts on or just past a timing line (some layouts; a layout without timing cones, whose line is
    // drawn through the start pose) begins its first lap when it first moves, as the stack's lap counter counts it
    // from the go (not through the seconds it stands in Ready); otherwise lap 1 begins at the first crossing.
    for (std::size_t g = 0; g < gates_.gates().size() && !open_; ++g) {
      const double past = gates_.past(g, pos);
      const Vec2 lat(-gates_.gates()[g].forward.y(), gates_.gates()[g].forward.x());
      if (past >= 0.0 && past < 10.0 &&
          std::fabs((pos - gates_.gates()[g].centre).dot(lat)) <= gates_.gates()[g].half_width)
        start_past_line_ = true;
    }
  } else {
    if (start_past_line_ && !lap_start_ && laps_.empty() && truth.speed() > 0.05) lap_start_ = last_->t;
    if (open_) {
      // An open layout has no start line of its own: the run is timed from the first motion to the end line.
      if (!lap_start_ && truth.speed() > 0.05) lap_start_ = last_->t;
      if (const auto f = crossing(end_gate_, last_->pose.position(), pos)) {
        crossed = end_gate_;
        t_cross = last_->t + (truth.t - last_->t) * *f;
      }
    } else if (const auto g = gates_.crossed(last_->pose.position(), pos)) {
      // Interpolate the crossing time for lap times better than one step.
      const double da = gates_.past(*g, last_->pose.position()), db = gates_.past(*g, pos);
      crossed = gates_.gates()[*g];
      t_cross = last_->t + (truth.t - last_->t) * (da / (da - db));
    }
  }
  if (crossed && !finished_) {
    const Stamp t = t_cross;
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
        finish_ = *crossed;
      }
    }
    lap_start_ = t;
    cte_sq_ = cte_max_ = v_max_ = 0;
    cte_n_ = 0;
  }
  // The EBS test: the AS went to Emergency on the lane after the start line (the stack's trigger).
  if (mission_ == Mission::EbsTest && !finished_ && lap_start_ && as_state_ == AsState::Emergency) {
    finished_ = true;
    ebs_trigger_at_ = pos;
    ebs_trigger_speed_ = truth.speed();
  }
  if (lap_start_ && !finished_) {
    const double cte = centre_distance(pos);
    cte_sq_ += cte * cte;
    cte_max_ = std::max(cte_max_, cte);
    ++cte_n_;
    v_max_ = std::max(v_max_, truth.speed());
  }
  if (finished_ && !stopped_after_finish_ && !left_stop_zone_) {
    if (mission_ == Mission::EbsTest) {
      // Stopped on the lane (the centre line ± 1.5 m), before the lane's end.
      if (ref_.distance(pos) > 1.5)
        left_stop_zone_ = true;
      else if (truth.speed() < 0.05) {
        stopped_after_finish_ = true;
        ebs_stop_distance_ = (pos - *ebs_trigger_at_).norm();
      }
    } else {
      // The skid pad leaves straight along its entry axis (its cones make no centre line there); other
      // layouts stop near their centre line.
      const Vec2 lat(-finish_.forward.y(), finish_.forward.x());
      const double off = mission_ == Mission::Skidpad ? std::fabs((pos - finish_.centre).dot(lat)) : ref_.distance(pos);
      if (past(finish_, pos) > stop_zone_m_ || off > (mission_ == Mission::Skidpad ? 2.0 : 4.0))
        left_stop_zone_ = true;
      else if (truth.speed() < 0.05)
        stopped_after_finish_ = true;
    }
  }
  last_ = truth;
}

void Scorecard::set_section(const std::string& key, const nlohmann::json& value) {
  sections_[key] = std::make_shared<const nlohmann::json>(value);
}

bool Scorecard::mission_succeeded() const { return failures().empty(); }

double milli(double v) { return std::round(v * 1e3) / 1e3; }

std::vector<std::string> Scorecard::failures() const {
  std::vector<std::string> why;
  if (cones_hit_ > 0) why.push_back(std::to_string(cones_hit_) + " cone(s) hit");
  if (!finished_)
    why.push_back("not finished: " + std::to_string(laps_.size()) + " of " + std::to_string(laps_to_finish_) +
                  (mission_ == Mission::Skidpad ? " timed circle(s)" : " lap(s)"));
  else if (!stopped_after_finish_)
    why.push_back(left_stop_zone_ ? "no stop in the zone after the finish (left it)" : "no stop after the finish");
  const AsState end = mission_ == Mission::EbsTest ? AsState::Emergency : AsState::Finished;
  if (as_state_ != end)
    why.push_back("AS ended " + std::string(to_string(as_state_)) + ", not " + std::string(to_string(end)));
  for (const auto& r : extra_reasons_) why.push_back(r);
  return why;
}

nlohmann::json Scorecard::to_json() const {
  using nlohmann::json;
  json j;
  const auto why = failures();
  j["verdict"] = why.empty() ? "pass" : "fail";
  j["verdict_reasons"] = why;
  j["track"] = track_.name;
  j["mission"] = std::string(to_string(mission_));
  j["seed"] = seed_;
  j["finished"] = finished_;
  j["stopped_after_finish"] = stopped_after_finish_;
  j["as_state"] = std::string(to_string(as_state_));
  j["sim_time_s"] = milli(sim_time_);
  j["wall_time_s"] = milli(wall_time_s_);
  j["cones_hit"] = cones_hit_;
  if (mission_ == Mission::Trackdrive || mission_ == Mission::Autocross) j["layout"] = open_ ? "open" : "loop";
  if (mission_ == Mission::EbsTest)
    j["ebs"] = {{"triggered", ebs_trigger_at_.has_value()},
                {"trigger_speed_m_s", milli(ebs_trigger_speed_)},
                {"stop_distance_m", milli(ebs_stop_distance_)}};
  j["laps"] = json::array();
  for (const auto& l : laps_)
    j["laps"].push_back({{"lap", l.lap},
                         {"time_s", milli(l.time_s)},
                         {"cte_rms_m", milli(l.cte_rms_m)},
                         {"cte_max_m", milli(l.cte_max_m)},
                         {"v_max_m_s", milli(l.v_max_m_s)}});
  j["vehicle"] = {{"mu", limits_.mu},
                  {"a_accel_max", limits_.a_accel_max},
                  {"a_brake_max", limits_.a_brake_max},
                  {"v_max", limits_.v_max}};
  j["latency_ms"] = latency_ms_ ? *latency_ms_ : json::object();
  j["faults"] = faults_json(faults_);
  for (const auto& [k, v] : sections_) j[k] = *v;
  return j;
}

nlohmann::json latency_json(const std::map<std::string, LatencyStats>& stages) {
  nlohmann::json lat = nlohmann::json::object();
  for (const auto& [stage, s] : stages)
    lat[stage] = {{"p50", std::round(s.quantile(0.5) * 1e6) / 1e3},
                  {"p99", std::round(s.quantile(0.99) * 1e6) / 1e3},
                  {"max", std::round(s.max() * 1e6) / 1e3},
                  {"n", s.count()}};
  return lat;
}

void Scorecard::set_latencies(const std::map<std::string, LatencyStats>& stages) {
  latency_ms_ = std::make_shared<const nlohmann::json>(latency_json(stages));
}

}  // namespace fsd
