#pragma once
// The scorecard's "map" section (DESIGN.md §8): the stack's cone map at the end of a run against the simulated
// world's true cones. Mapped and true cones are paired one to one, nearest pairs first, within a gate; a true
// cone left unpaired is missed, a mapped one a ghost. Position error and colour are judged on the pairs.
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "common/track.hpp"
#include "common/types.hpp"

namespace fsd {

struct MapScore {
  int true_cones = 0, mapped = 0, matched = 0, missed = 0, ghosts = 0;
  double rmse_m = 0;           // over the pairs (0 with none)
  double colour_accuracy = 0;  // share of pairs whose mapped colour is the true one (0 with none)
};

// `gate`: half the 1 m between a start line's neighbouring cones, so that a pair is one cone, not its neighbour.
MapScore score_map(const std::vector<TrackCone>& truth, const std::vector<Cone>& mapped, double gate = 0.5);
nlohmann::json to_json(const MapScore& score);

}  // namespace fsd
