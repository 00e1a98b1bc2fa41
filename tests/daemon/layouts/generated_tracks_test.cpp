// Control on layouts it has never seen: generated layouts (`fsd track generate`) driven end to end by the fsd
// binary (headless lockstep, truth perception, LiDAR and camera off), judged by the scorecard against the virtual
// car's truth. Trackdrive 2 laps, autocross 1, acceleration, skid pad. Odd seeds are the rules' layouts, even seeds
// have the classes of public layouts mixed in (`--irregular`: hairpin chains, a whole lap round one 9 m turn,
// hand-placed cones, an inside cone out of its ring, a lane narrowed below 3 m, a braking zone closed 25 m after the
// finish; docs/track-generator.md).
//   GeneratedTracks.CiSubset     the CI subset: 40 layouts of every kind, two at a time; >= 99.5 % must be clean
//                                (finished, no cone hit, stopped in the zone); every other one is listed
//   GeneratedTracksSweep.DISABLED_Full   the whole sweep, by hand (docs/control.md "Generated layouts"):
//       build/tests/test_daemon --gtest_also_run_disabled_tests --gtest_filter='GeneratedTracksSweep.*'
//     seeds 1–200 of trackdrive and autocross, 1–100 of acceleration and skid pad (FSD_SWEEP_SEEDS=N for
//     1–N of every kind, FSD_SWEEP_JOBS=J runs, 2 by default); prints every failure with its seed, kind and
//     reason, then a summary table and the lap-2 figures.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <regex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "tests/daemon/fsd_process.hpp"
#include "tests/daemon/layouts/friction_limited_lap.hpp"
#include "tests/scratch_dir.hpp"
#include "tests/truth_sources.hpp"

namespace fsd {
namespace {

using test::run_fsd;
using test::scratch_path;

struct Case {
  std::string kind;  // trackdrive | autocross | acceleration | skidpad
  int seed = 1;
};

struct Outcome {
  Case c;
  bool ran = false, clean = false;
  bool finished = false, stopped = false;
  int rc = -1, cones_hit = 0;
  std::string as_state, reason, command;
  std::vector<double> laps;
  double reference = 0;  // trackdrive: friction-limited lap time of the true centre line
  double length = 0;     // and that centre line's length
};

std::string fast_config() {
  const std::string path = scratch_path("fsd_fast_generated.json");
  if (!std::filesystem::exists(path)) std::ofstream(path) << test::truth_sources();
  return path;
}

// "cone hit at 12.34 s: yellow cone at (1.00, 2.00); car at ..." lines of the log, as "yellow (1.00, 2.00)".
std::vector<std::string> cone_hits(const std::string& log) {
  static const std::regex re(R"(cone hit at [0-9.]+ s: (\w+) cone at \(([-0-9.]+), ([-0-9.]+)\))");
  std::vector<std::string> hits;
  for (auto it = std::sregex_iterator(log.begin(), log.end(), re); it != std::sregex_iterator(); ++it)
    hits.push_back((*it)[1].str() + " (" + (*it)[2].str() + ", " + (*it)[3].str() + ")");
  return hits;
}

// Generates the layout with the CLI, drives it, judges the scorecard.
Outcome drive(const Case& c) {
  Outcome o;
  o.c = c;
  const std::string stem = "gen_" + c.kind + "_" + std::to_string(c.seed);
  const std::string track = scratch_path(stem + ".csv"), report = scratch_path(stem + ".json");
  std::string log;
  const std::string gen = "track generate --kind " + c.kind + " --seed " + std::to_string(c.seed) +
                          (c.seed % 2 == 0 ? " --irregular" : "");
  if (run_fsd(gen + " --out " + track, &log) != 0) {
    o.reason = "generator failed: " + log;
    return o;
  }
  const bool td = c.kind == "trackdrive";
  o.command = "fsd " + gen + " --out t.csv && fsd run --sim --headless --until-finished --config fast.json" +
              " --mission " + c.kind + (td ? " --laps 2" : "") + " --track t.csv --report r.json";
  std::remove(report.c_str());
  o.rc = run_fsd("run --sim --headless --until-finished --config " + fast_config() + " --mission " + c.kind +
                     (td ? " --laps 2" : "") + " --track " + track + " --report " + report,
                 &log);
  std::ifstream f(report);
  const nlohmann::json r = f.good() ? nlohmann::json::parse(f, nullptr, false) : nlohmann::json();
  if (!r.is_object()) {
    o.reason = "no report (exit " + std::to_string(o.rc) + ")";
    return o;
  }
  o.ran = true;
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
    const test::Limits lim{v["mu"].get<double>(), v["a_accel_max"].get<double>(), v["a_brake_max"].get<double>(),
                           v["v_max"].get<double>()};
    o.reference = test::friction_limited_lap_time(test::read_cones(track), lim, &o.length);
  }
  return o;
}

std::string describe(const Outcome& o) {
  std::ostringstream s;
  s << o.c.kind << " seed " << o.c.seed << ": " << (o.clean ? "clean" : o.reason);
  for (std::size_t i = 0; i < o.laps.size(); ++i) s << (i ? ", " : " | laps ") << o.laps[i] << " s";
  if (o.reference > 0 && o.laps.size() >= 2)
    s << " | lap 2 vs friction-limited " << o.reference << " s: " << (100.0 * (o.laps[1] / o.reference - 1.0)) << " %";
  return s.str();
}

// Drives every case on `jobs` worker threads (each runs fsd processes), printing each outcome as it comes.
std::vector<Outcome> drive_all(const std::vector<Case>& cases, int jobs) {
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

// ---------------------------------------------------------------------------------------------------------------
// The CI subset: ≥ 40 layouts mixing every kind, each its own test (ctest runs them in parallel).
std::vector<Case> ci_cases() {
  std::vector<Case> v;
  for (int s = 1; s <= 14; ++s) v.push_back({"trackdrive", s});
  for (int s = 1; s <= 12; ++s) v.push_back({"autocross", s});
  for (int s = 1; s <= 7; ++s) v.push_back({"acceleration", s});
  for (int s = 1; s <= 7; ++s) v.push_back({"skidpad", s});
  return v;
}

// The subset as one test, two layouts at a time: every failure is listed with its seed and how to reproduce it.
// Held to the issue's target over the whole sweep, >= 99.5 % clean (of 40: every one; the runs are deterministic);
// docs/control.md "Generated layouts" has the whole sweep's figures.
TEST(GeneratedTracks, CiSubset) {
  const std::vector<Case> cases = ci_cases();
  const std::vector<Outcome> out = drive_all(cases, 2);
  int clean = 0;
  for (const auto& o : out) {
    EXPECT_TRUE(o.ran) << describe(o);
    clean += o.clean;
    if (!o.clean) std::printf("NOT CLEAN: %s\n  reproduce: %s\n", describe(o).c_str(), o.command.c_str());
    if (o.c.kind == "trackdrive" && o.clean) {
      ASSERT_EQ(o.laps.size(), 2u) << describe(o);
      ASSERT_GT(o.reference, 0.0) << describe(o);
      // Lap 2 on the recorded line: not faster than the friction limit allows (the reference would be wrong).
      EXPECT_GE(o.laps[1], 0.85 * o.reference) << describe(o);
    }
  }
  std::printf("clean %d of %zu\n", clean, out.size());
  EXPECT_GE(clean, static_cast<int>(std::ceil(0.995 * static_cast<double>(out.size()))))
      << "more than 0.5 % of the CI subset is not clean (listed above)";
}

// ---------------------------------------------------------------------------------------------------------------
// The whole sweep, by hand.
TEST(GeneratedTracksSweep, DISABLED_Full) {
  const char* seeds_env = std::getenv("FSD_SWEEP_SEEDS");
  const char* jobs_env = std::getenv("FSD_SWEEP_JOBS");
  const int loops = seeds_env ? std::atoi(seeds_env) : 200, events = seeds_env ? loops : 100;
  const int jobs = std::max(1, jobs_env ? std::atoi(jobs_env) : 2);
  std::vector<Case> cases;
  for (int s = 1; s <= loops; ++s) cases.push_back({"trackdrive", s});
  for (int s = 1; s <= loops; ++s) cases.push_back({"autocross", s});
  for (int s = 1; s <= events; ++s) cases.push_back({"acceleration", s});
  for (int s = 1; s <= events; ++s) cases.push_back({"skidpad", s});
  const std::vector<Outcome> out = drive_all(cases, jobs);
  std::printf("\nFailures:\n");
  for (const auto& o : out)
    if (!o.clean) std::printf("  %s\n    reproduce: %s\n", describe(o).c_str(), o.command.c_str());
  std::printf(
      "\n| kind | layouts | clean | finished | with cones hit | no stop in zone |\n|---|---|---|---|---|---|\n");
  std::map<std::string, std::array<int, 5>> sum;
  for (const auto& o : out) {
    auto& s = sum[o.c.kind];
    ++s[0];
    s[1] += o.clean;
    s[2] += o.finished;
    s[3] += o.cones_hit != 0;
    s[4] += o.finished && !o.stopped;
  }
  int all = 0, clean = 0;
  for (const auto& [k, s] : sum) {
    std::printf("| %s | %d | %d (%.1f %%) | %d | %d | %d |\n", k.c_str(), s[0], s[1], 100.0 * s[1] / s[0], s[2], s[3],
                s[4]);
    all += s[0], clean += s[1];
  }
  // Lap 2 against each trackdrive layout's friction-limited reference.
  std::vector<double> ratio;
  std::printf(
      "\n| trackdrive seed | centre line (m) | lap 1 (s) | lap 2 (s) | reference (s) | lap 2 vs reference |\n"
      "|---|---|---|---|---|---|\n");
  for (const auto& o : out)
    if (o.c.kind == "trackdrive" && o.laps.size() >= 2 && o.reference > 0) {
      ratio.push_back(o.laps[1] / o.reference - 1.0);
      std::printf("| %d | %.0f | %.2f | %.2f | %.2f | %+.1f %%%s |\n", o.c.seed, o.length, o.laps[0], o.laps[1],
                  o.reference, 100.0 * ratio.back(), o.clean ? "" : " (not clean)");
    }
  if (!ratio.empty()) {
    std::sort(ratio.begin(), ratio.end());
    std::printf("\nlap 2 vs reference over %zu layouts: median %+.1f %%, 90th percentile %+.1f %%, max %+.1f %%\n",
                ratio.size(), 100.0 * ratio[ratio.size() / 2], 100.0 * ratio[ratio.size() * 9 / 10],
                100.0 * ratio.back());
  }
  std::printf("\nclean %d of %d (%.1f %%)\n", clean, all, 100.0 * clean / std::max(1, all));
  EXPECT_GE(clean, 0.995 * all) << "the issue's target: ≥ 99.5 % clean";
}

}  // namespace
}  // namespace fsd
