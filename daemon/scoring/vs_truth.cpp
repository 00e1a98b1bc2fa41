#include "daemon/scoring/vs_truth.hpp"

#include <algorithm>
#include <string>

#include <nlohmann/json.hpp>

#include "daemon/scoring/scorecard.hpp"

namespace fsd {

using nlohmann::json;

Config truth_reference_config(const Config& cfg) {
  Config c = cfg;
  const std::string why = "--vs-truth";
  c.set("run.perception_source", std::string("truth"), why);
  c.set("run.localization_source", std::string("truth"), why);
  c.set("sim.enable_lidar", false, why);
  c.set("sim.enable_camera", false, why);
  return c;
}

namespace {

const json* lap_of(const json& report, int lap) {
  if (!report.contains("laps")) return nullptr;
  for (const auto& l : report["laps"])
    if (l.value("lap", 0) == lap) return &l;
  return nullptr;
}

}  // namespace

json vs_truth(const json& estimated, const json& truth) {
  json out = {{"source", "truth"},
              {"finished", truth.value("finished", false)},
              {"cones_hit", truth.value("cones_hit", 0)},
              {"verdict", truth.value("verdict", "fail")},
              {"laps", json::array()}};
  int last = 0;
  for (const json* r : {&estimated, &truth})
    if (r->contains("laps"))
      for (const auto& l : (*r)["laps"]) last = std::max(last, l.value("lap", 0));
  for (int lap = 1; lap <= last; ++lap) {
    const json* e = lap_of(estimated, lap);
    const json* t = lap_of(truth, lap);
    json row = {{"lap", lap}};
    if (e) {
      row["time_s"] = (*e)["time_s"];
      row["cte_rms_m"] = (*e)["cte_rms_m"];
      row["cte_max_m"] = (*e)["cte_max_m"];
    }
    if (t) {
      row["truth_time_s"] = (*t)["time_s"];
      row["truth_cte_rms_m"] = (*t)["cte_rms_m"];
      row["truth_cte_max_m"] = (*t)["cte_max_m"];
    }
    if (e && t && (*t)["time_s"].get<double>() > 0)
      row["time_delta_pct"] =
          milli(100.0 * ((*e)["time_s"].get<double>() / (*t)["time_s"].get<double>() - 1.0));
    out["laps"].push_back(row);
  }
  return out;
}

}  // namespace fsd
