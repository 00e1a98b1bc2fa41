#pragma once
// Localization against the cone map: each perception frame's cones are paired with the mapped cones near where the
// pose puts them, and the rigid motion that lays the pairs onto the map is a pose measurement of the fusion filter
// while no GNSS fix is recent (daemon/stack/fused_localization.hpp): always without satellites, where the map (from
// lap 2 on the one lap 1 built and closed) is the only absolute reference. A match also tells control that the pose
// agrees with the map. Pure: no I/O, no clock.
#include <optional>
#include <vector>

#include "common/config.hpp"
#include "common/geometry.hpp"
#include "common/types.hpp"

namespace fsd {

struct MapMatchConfig {
  bool enabled = true;
  double gate = 0.7;        // m: a detection pairs with the nearest mapped cone this close (where the pose puts it)
  double max_range = 15.0;  // m: detections farther away are not used (their position is less sure)
  int min_pairs = 4;        // fewer pairs: no correction (a straight of one row constrains nothing across)
  double max_step = 0.3;    // m: an alignment moving the pose more than this is no match (a wrong pairing)
  // No GNSS fix recent: a frame's alignment is a pose measurement of the fusion filter, this sure.
  double fused_sigma = 0.10;      // m per axis
  double fused_yaw_sigma = 0.02;  // rad
};
const ConfigSection<MapMatchConfig>& map_match_section();  // "localization.map_match"

struct MapMatch {
  Pose2 alignment;  // map ← estimated: the pose measurement (applied to the estimate it was matched at)
  int pairs = 0;
  double rms_before = 0, rms_after = 0;  // m, of the pairs, before and after the full alignment
};

// `detections`: one frame's cones in the vehicle frame; `pose`: the estimate then (map ← vehicle); `map`: the
// cone map (map frame). Nothing when there are too few pairs or the alignment is implausible.
std::optional<MapMatch> match_to_map(const std::vector<Cone>& detections, const Pose2& pose,
                                     const std::vector<Cone>& map, const MapMatchConfig& cfg = {});

}  // namespace fsd
