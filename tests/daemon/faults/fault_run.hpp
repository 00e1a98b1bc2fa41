#pragma once
// Fault runs through the whole stack, as a user runs them: `fsd run --sim --headless --until-finished` with a fault
// schedule (sim.faults.*) on epfl_track_1, and what the scorecard says of it: the stack's own fault log ("faults")
// and the truth trace kept around each injected fault ("injected_faults").
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "tests/daemon/fsd_process.hpp"
#include "tests/scratch_dir.hpp"
#include "tests/truth_sources.hpp"

namespace fsd::test {

using nlohmann::json;

struct FsdRun {
  int rc = -1;
  std::string log;
  json report;
};

// How a fault run perceives and localizes: the truth sources (the reaction of control alone; `Lidar` also simulates
// the VLP-16, whose silence then starves perception through the scan builder), or the real stack (the defaults:
// LiDAR and camera stages, GNSS-INS fused with the wheels and the LiDAR odometry).
enum class Sources { Truth, TruthWithLidar, Real };

// Runs fsd on epfl_track_1 (2 laps) with `faults` as the sim.faults section; `max_sim_time` > 0 ends the run early
// (the mission is then not finished).
inline FsdRun run_with_faults(const std::string& name, const json& faults, Sources sources = Sources::Truth,
                              double max_sim_time = 0) {
  const std::string config = scratch_path(name + ".json"), out = scratch_path(name + "_report.json");
  json cfg = sources == Sources::Real
                 ? json{{"sim", json::object()}, {"run", json::object()}}
                 : truth_sources_json({{"sim", {{"enable_lidar", sources == Sources::TruthWithLidar}}}});
  if (!faults.is_null()) cfg["sim"]["faults"] = faults;
  if (max_sim_time > 0) cfg["run"]["max_sim_time"] = max_sim_time;
  std::ofstream(config) << cfg.dump();
  const std::string args =
      "run --sim --headless --until-finished --track ../shared/tracks/epfl_track_1.csv"
      " --laps 2 --config " +
      config + " --report " + out;
  FsdRun r;
  r.rc = test::run_fsd(args, &r.log);
  std::ifstream f(out);
  if (f) r.report = json::parse(f);
  return r;
}

// The scorecard's record of the one injected fault, with its window opened.
inline const json& injected(const FsdRun& r, const std::string& fault) {
  static const json none;
  for (const auto& f : r.report["injected_faults"])
    if (f["fault"] == fault && !f["start_s"].is_null()) return f;
  ADD_FAILURE() << "no opened window for " << fault << " in " << r.report["injected_faults"].dump();
  return none;
}

// The stack's faults of one source.
inline std::vector<json> faults_of(const FsdRun& r, const std::string& source) {
  std::vector<json> out;
  for (const auto& f : r.report["faults"])
    if (f["source"] == source) out.push_back(f);
  return out;
}

// Truth speed at the first trace sample at or after t.
inline double speed_at(const json& fault, double t) {
  const auto& ts = fault["trace"]["t_s"];
  for (std::size_t i = 0; i < ts.size(); ++i)
    if (ts[i].get<double>() >= t - 1e-6) return fault["trace"]["speed_m_s"][i].get<double>();
  ADD_FAILURE() << "trace ends before " << t;
  return -1;
}

// The reaction to a LiDAR lost for 1 s on lap 1, from the scorecard of a run.
inline void expect_slowed_and_recovered(const FsdRun& r) {
  const json& rep = r.report;
  EXPECT_EQ(rep["cones_hit"], 0);
  const json& inj = injected(r, "lidar");
  const double start = inj["start_s"].get<double>(), end = inj["end_s"].get<double>();
  // The supervisor (control.supervisor.lidar_timeout 0.3 s) capped the speed to 3 m/s and did not stop.
  const auto lidar = faults_of(r, "lidar");
  ASSERT_EQ(lidar.size(), 1u) << rep["faults"].dump();
  EXPECT_EQ(lidar[0]["what"], "detections stale");
  EXPECT_EQ(lidar[0]["action"], "slow down to 3.00 m/s");
  // Last detections at most one perception period (0.1 s) before the start; stale 0.3 s later.
  EXPECT_GE(lidar[0]["t"].get<double>(), start + 0.3 - 0.1);
  EXPECT_LE(lidar[0]["t"].get<double>(), start + 0.3 + 0.02);
  // Nothing else went wrong around the outage (until 3 s after it), and nothing stopped the car.
  for (const auto& f : rep["faults"]) {
    if (f["source"] != "lidar") {
      EXPECT_GT(f["t"].get<double>(), end + 3.0) << f.dump();
    }
    EXPECT_NE(f["action"], "controlled stop") << f.dump();
  }
  // From the truth: the car was well above the cap, slowed down by more than 3 m/s within the outage, and sped
  // up again once cones came back.
  const double v0 = inj["speed_at_start_m_s"].get<double>();
  EXPECT_GT(v0, 6.0);
  double v_min = 1e9, v_after = 0;
  const auto& ts = inj["trace"]["t_s"];
  const auto& vs = inj["trace"]["speed_m_s"];
  for (std::size_t i = 0; i < ts.size(); ++i) {
    const double t = ts[i].get<double>(), v = vs[i].get<double>();
    if (t >= start && t <= end + 0.1) v_min = std::min(v_min, v);
    if (t >= end + 0.1) v_after = std::max(v_after, v);
  }
  EXPECT_LT(v_min, v0 - 3.0);
  EXPECT_GT(v_min, 1.0);  // slowed, not stopped
  EXPECT_GT(v_after, v_min + 2.0);
  EXPECT_TRUE(inj["stopped_at_s"].is_null());
}

}  // namespace fsd::test
