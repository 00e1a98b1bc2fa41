// Perception on layouts with dense cones (issue: "perception on any layout"): 40 generated layouts driven end to
// end by the fsd binary on the defaults (the real pipeline: LiDAR + camera, fused localization, distractors on),
// each judged on its scorecard's perception and lap-1 map sections against the virtual car's truth:
//   recall_visible_15m >= 0.97, precision >= 0.99, verified colour within 12 m >= 0.98,
//   lap-1 map colour >= 0.98 and RMSE <= 0.10 m.
// 15 trackdrive and 15 autocross layouts with cones 1.5-2 m apart along the boundaries and 0.3 rad of arc between
// them in turns (0.45 m on the inner ring of the tightest hairpin, 1.35 m on its outer), even seeds with the irregular
// classes mixed in (hand-placed cones up to 0.25 m off their place: the generator needs 1.5 m of spacing for them);
// 10 skid pads (the rules' figure). Prints one row per layout and the layouts that miss a figure;
// exits 1 when any does. About 15 min on 2 cores. From the project root:
//   build/bench/dense_cones_sweep
// FSD_SWEEP_SEEDS=N: seeds 1..N of each loop kind (N / 3 skid pads, at least 1); FSD_SWEEP_JOBS=J: J runs at a time;
// FSD_BINARY=path: run that fsd (a copy) instead of the build's, which a rebuild meanwhile would replace.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "tests/daemon/layouts/generated_layouts.hpp"

namespace {

double number(const nlohmann::json& section, const char* key) {
  return section.is_object() && section.contains(key) && section[key].is_number() ? section[key].get<double>() : -1.0;
}

}  // namespace

int main() {
  using fsd::test::generated::Case;
  const char* seeds_env = std::getenv("FSD_SWEEP_SEEDS");
  const char* jobs_env = std::getenv("FSD_SWEEP_JOBS");
  const int loops = seeds_env ? std::max(1, std::atoi(seeds_env)) : 15;
  const int pads = std::max(1, seeds_env ? loops / 3 : 10);
  const int jobs = std::max(1, jobs_env ? std::atoi(jobs_env) : 2);
  const std::string dense = "--cone-spacing-min 1.5 --cone-spacing-max 2 --turn-angle 0.3";
  const std::string defaults = fsd::test::scratch_path("defaults.json");
  std::ofstream(defaults) << "{}";  // the shipped defaults: the real pipeline
  std::vector<Case> cases;
  for (int s = 1; s <= loops; ++s) cases.push_back({"trackdrive", s, dense, defaults});
  for (int s = 1; s <= loops; ++s) cases.push_back({"autocross", s, dense, defaults});
  for (int s = 1; s <= pads; ++s) cases.push_back({"skidpad", s, "", defaults});
  const auto out = fsd::test::generated::drive_all(cases, jobs);

  std::printf(
      "\n| layout | clean | precision | recall 15 m | recall visible 15 m | verified colour 12 m | lap-1 map colour | "
      "lap-1 map RMSE (m) |\n|---|---|---|---|---|---|---|---|\n");
  std::vector<std::string> missed;
  for (const auto& o : out) {
    const auto& p = o.report.is_object() ? o.report["perception"] : nlohmann::json();
    // The lap-1 map where a lap was timed; the map at the end of the run otherwise (autocross's one lap).
    const auto& m = o.report.is_object() && o.report.contains("map_lap1") ? o.report["map_lap1"]
                    : o.report.is_object()                                ? o.report["map"]
                                                                          : nlohmann::json();
    const double prec = number(p, "precision"), rec = number(p, "recall_15m"), vis = number(p, "recall_visible_15m");
    const double col = number(p, "verified_colour_accuracy_12m"), mcol = number(m, "colour_accuracy");
    const double rmse = number(m, "rmse_m");
    const std::string name = o.c.kind + " " + std::to_string(o.c.seed);
    std::printf("| %s | %s | %.4f | %.4f | %.4f | %.4f | %.4f | %.3f |\n", name.c_str(), o.clean ? "yes" : "no", prec,
                rec, vis, col, mcol, rmse);
    std::string why;
    auto need = [&](bool ok, const std::string& what) {
      if (!ok) why += (why.empty() ? "" : ", ") + what;
    };
    need(o.ran, "no report: " + o.reason);
    need(vis >= 0.97, "recall_visible_15m " + std::to_string(vis));
    need(prec >= 0.99, "precision " + std::to_string(prec));
    need(col >= 0.98, "verified colour " + std::to_string(col));
    need(mcol >= 0.98, "map colour " + std::to_string(mcol));
    need(rmse >= 0 && rmse <= 0.10, "map RMSE " + std::to_string(rmse));
    if (!why.empty()) missed.push_back(name + ": " + why + "\n    reproduce: " + o.command);
  }
  std::printf("\n%zu of %zu layouts meet every figure\n", out.size() - missed.size(), out.size());
  for (const auto& m : missed) std::printf("  %s\n", m.c_str());
  return missed.empty() ? 0 : 1;
}
