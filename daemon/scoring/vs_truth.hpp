#pragma once
// `fsd run --sim --vs-truth`: what the estimates cost. The same layout and seed are driven a second time on the
// truth sources (the simulator's cones and pose, DESIGN.md §8); the scorecard gains "vs_truth", the two runs' laps
// side by side.
#include <nlohmann/json_fwd.hpp>

#include "common/config.hpp"

namespace fsd {

// The run's configuration with the truth sources: run.perception_source = run.localization_source = truth, and
// the LiDAR and camera models off (truth perception does not read them; the vehicle and the layout are the same).
Config truth_reference_config(const Config& cfg);

// "vs_truth" from the run's scorecard and the reference run's: {"source": "truth", "finished", "cones_hit",
// "verdict", "laps": [{"lap", "time_s", "truth_time_s", "time_delta_pct", "cte_rms_m", "truth_cte_rms_m",
// "cte_max_m", "truth_cte_max_m"}, ...]}; a lap only one run drove carries its side alone.
nlohmann::json vs_truth(const nlohmann::json& estimated, const nlohmann::json& truth);

}  // namespace fsd
