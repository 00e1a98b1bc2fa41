#pragma once
// Control on layouts it has never seen: a generated layout (`fsd track generate`) driven end to end by the fsd
// binary (headless lockstep, the truth sources, LiDAR and camera off) and judged by the scorecard against the
// virtual car's truth. Trackdrive 2 laps, autocross 1, acceleration, skid pad. Odd seeds are the rules' layouts,
// even seeds have the classes of public layouts mixed in (`--irregular`; docs/track-generator.md).
// Used by the CI subset (tests/daemon/layouts/generated_tracks_test.cpp) and the whole sweep
// (bench/generated_layouts_sweep.cpp). Needs FSD_BINARY (tests/daemon/fsd_process.hpp).
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <regex>
#include <sstream>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "tests/daemon/fsd_process.hpp"
#include "tests/daemon/layouts/friction_limited_lap.hpp"
#include "tests/scratch_dir.hpp"
#include "tests/truth_sources.hpp"

namespace fsd::test::generated {

struct Case {
  Case() = default;
  Case(std::string k, int s, std::string options = {}, std::string cfg = {})
      : kind(std::move(k)), seed(s), generator_options(std::move(options)), config(std::move(cfg)) {}
  std::string kind;  // trackdrive | autocross | acceleration | skidpad
  int seed = 1;
  std::string generator_options;  // more `fsd track generate` options (e.g. denser cones)
  std::string config;             // the run's config file; empty: the truth sources (fast_config())
};

struct Outcome {
  Case c;
  bool ran = false, clean = false;
  bool finished = false, stopped = false;
  int rc = -1, cones_hit = 0;
  std::string as_state, reason, command;
  std::vector<double> laps;
  double reference = 0;   // trackdrive: friction-limited lap time of the true centre line
  double length = 0;      // and that centre line's length
  nlohmann::json report;  // the whole scorecard
};

inline std::string fast_config() {
  const std::string path = scratch_path("fsd_fast_generated.json");
  if (!std::filesystem::exists(path)) std::ofstream(path) << truth_sources();
  return path;
}

// "cone hit at 12.34 s: yellow cone at (1.00, 2.00); car at ..." lines of the log, as "yellow (1.00, 2.00)".
inline std::vector<std::string> cone_hits(const std::string& log) {
  static const std::regex re(R"(cone hit at [0-9.]+ s: (\w+) cone at \(([-0-9.]+), ([-0-9.]+)\))");
  std::vector<std::string> hits;
  for (auto it = std::sregex_iterator(log.begin(), log.end(), re); it != std::sregex_iterator(); ++it)
    hits.push_back((*it)[1].str() + " (" + (*it)[2].str() + ", " + (*it)[3].str() + ")");
  return hits;
}

// Generates the layout with the CLI, drives it, judges the scorecard: clean is finished, no cone hit, stopped in
// the zone, AS Finished, exit 0.
inline Outcome drive(const Case& c) {
  Outcome o;
  o.c = c;
  const std::string stem = "gen_" + c.kind + "_" + std::to_string(c.seed);
  const std::string track = scratch_path(stem + ".csv"), report = scratch_path(stem + ".json");
  std::string log;
  const std::string gen = "track generate --kind " + c.kind + " --seed " + std::to_string(c.seed) +
                          (c.seed % 2 == 0 ? " --irregular" : "") +
                          (c.generator_options.empty() ? "" : " " + c.generator_options);
  const std::string config = c.config.empty() ? fast_config() : c.config;
  if (run_fsd(gen + " --out " + track, &log) != 0) {
    o.reason = "generator failed: " + log;
    return o;
  }
  const bool td = c.kind == "trackdrive";
  o.command = "fsd " + gen + " --out t.csv && fsd run --sim --headless --until-finished --config " +
              (c.config.empty() ? std::string("fast.json") : c.config) + " --mission " + c.kind +
              (td ? " --laps 2" : "") + " --track t.csv --report r.json";
  std::remove(report.c_str());
  o.rc = run_fsd("run --sim --headless --until-finished --config " + config + " --mission " + c.kind +
                     (td ? " --laps 2" : "") + " --track " + track + " --report " + report,
                 &log);
  std::ifstream f(report);
  const nlohmann::json r = f.good() ? nlohmann::json::parse(f, nullptr, false) : nlohmann::json();
  if (!r.is_object()) {
    o.reason = "no report (exit " + std::to_string(o.rc) + ")";
    return o;
  }
  o.ran = true;
  o.report = r;
  o.finished = r.value("finished", false);
  o.stopped = r.value("stopped_after_finish", false);
  o.cones_hit = r.value("cones_hit", -1);
  o.as_state = r.value("as_state", "");
  for (const auto& l : r["laps"]) o.laps.push_back(l.value("time_s", 0.0));
  std::vector<std::string> why;
  if (!o.finished) why.push_back("not finished (" + std::to_string(o.laps.size()) + " lap(s), AS " + o.as_state + ")");
  if (o.cones_hit != 0) {
    std::string s = std::to_string(o.cones_hit) + " cone(s) hit:";
    for (const auto& h : cone_hits(log)) s += " " + h;
    why.push_back(s);
  }
  if (o.finished && !o.stopped) why.push_back("no stop in the zone after the finish");
  if (o.finished && o.as_state != "Finished") why.push_back("AS " + o.as_state);
  if (why.empty() && o.rc != 0) why.push_back("exit " + std::to_string(o.rc));
  for (const auto& w : why) o.reason += (o.reason.empty() ? "" : "; ") + w;
  o.clean = why.empty();
  if (td && r.contains("vehicle")) {
    const auto& v = r["vehicle"];
    const Limits lim{v["mu"].get<double>(), v["a_accel_max"].get<double>(), v["a_brake_max"].get<double>(),
                     v["v_max"].get<double>()};
    o.reference = friction_limited_lap_time(read_cones(track), lim, &o.length);
  }
  return o;
}

inline std::string describe(const Outcome& o) {
  std::ostringstream s;
  s << o.c.kind << " seed " << o.c.seed << ": " << (o.clean ? "clean" : o.reason);
  for (std::size_t i = 0; i < o.laps.size(); ++i) s << (i ? ", " : " | laps ") << o.laps[i] << " s";
  if (o.reference > 0 && o.laps.size() >= 2)
    s << " | lap 2 vs friction-limited " << o.reference << " s: " << (100.0 * (o.laps[1] / o.reference - 1.0)) << " %";
  return s.str();
}

// Drives every case on `jobs` worker threads (each runs fsd processes), printing each outcome as it comes.
inline std::vector<Outcome> drive_all(const std::vector<Case>& cases, int jobs) {
  fast_config();  // written once, before the workers read it
  std::vector<Outcome> out(cases.size());
  std::mutex print;
  std::size_t next = 0;
  auto worker = [&] {
    for (;;) {
      std::size_t i;
      {
        std::lock_guard<std::mutex> lock(print);
        if (next >= cases.size()) return;
        i = next++;
      }
      out[i] = drive(cases[i]);
      std::lock_guard<std::mutex> lock(print);
      std::printf("%s\n", describe(out[i]).c_str());
      std::fflush(stdout);
    }
  };
  std::vector<std::thread> pool;
  for (int j = 0; j < jobs; ++j) pool.emplace_back(worker);
  for (auto& t : pool) t.join();

  return out;
}

}  // namespace fsd::test::generated
