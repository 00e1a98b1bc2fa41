#pragma once
// What `fsd run` was asked to do (DESIGN.md §9), after the command line is parsed and before the config is read.
#include <optional>
#include <string>

namespace fsd {

struct RunOptions {
  std::string config_file;  // empty: compiled-in defaults
  bool sim = false;
  std::optional<std::string> track;  // overrides run.track
  std::optional<std::string> mission;
  std::optional<int> laps;
  std::optional<int> seed;
  std::optional<int> port;  // overrides web.port
  std::string replay,
      record;         // --replay FILE (daemon/feeders/replay_run.hpp), --record FILE (daemon/recording/recorder.hpp)
  double rate = 1.0;  // --rate: a replay with the dashboard at this multiple of real time
  bool headless = false;
  bool workers = false;  // --workers: headless too, the slow jobs on the Stack's threads as on the car (not repeatable)
  bool until_finished = false;
  std::string report;  // scorecard JSON path, empty: none
  std::string
      map_out;       // --map-out: the cone map at the end as a track CSV (daemon/scoring/map_export.hpp), empty: none
  bool vs_truth = false;  // --vs-truth: with --sim, the same layout and seed on the truth sources too (daemon/scoring/vs_truth.hpp)
  std::string role;  // --role perception: split mode's perception process (daemon/dds/perception_role.hpp)
};

}  // namespace fsd
