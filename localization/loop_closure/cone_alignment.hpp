#pragma once
// Finding the loop: back near the start, the cones seen now (placed by the drifted pose) are the cones mapped at
// the start, moved by the drift. The rigid 2-D transform that brings the current cones onto the reference cones
// with the most same-coloured pairs within a tolerance is the loop's correction; the pairs are the same cones
// (LapGraph::same_cone).
//
// Every hypothesis from two current cones and two reference cones of the same colours, as far apart as each
// other and within the drift bound of where they are, is tried (no random sampling: the same input gives the same
// loop); the best is refined by least squares over its pairs. A hypothesis is consistent when at most
// `max_unpaired` current cones land near a reference cone (within `landing_radius`) without pairing (a copy of a
// paired cone, within `copy_radius` of it, does not count: the lap's landmarks hold a cone twice where the pose
// jumped between its sightings): the right one leaves none but noise, one slid by a cone spacing leaves the cones
// that make the scene unlike itself (a start line's big orange cones landing by blue ones) unpaired. The answer is
// the consistent hypothesis with the most pairs; it is accepted only when no consistent hypothesis elsewhere
// (shifted by more than twice the tolerance) pairs `rival_min_pairs`. A symmetric scene (a straight lane, an arc of
// one radius) slid along itself by a spacing is consistent, so it is ambiguous; counting pairs alone is not enough:
// a scene cut off at its ends (the start seen driving out, the same lane seen coming back) slid by a spacing can
// pair more cones than the right answer.
#include <optional>
#include <utility>
#include <vector>

#include "common/types.hpp"

namespace fsd::loop_closure {

struct ConeAlignmentConfig {
  double max_drift = 4.0;       // m: how far a current cone may be from its reference (the drift over a lap)
  double max_rotation = 0.2;    // rad: the heading drift over a lap
  double pair_tolerance = 0.3;  // m: a pair after the transform
  int min_pairs = 4;            // fewer: no loop
  double landing_radius = 2.0;  // m: a current cone this close to a reference cone after the transform should pair
  int max_unpaired = 2;         // consistent: at most this many cones landed near a reference cone unpaired
  double copy_radius = 1.0;     // m: an unpaired cone this near a paired one of its colour is its copy
  int rival_min_pairs = 3;      // a consistent hypothesis elsewhere with this many pairs makes the scene ambiguous
};

struct ConeAlignment {
  Pose2 correction;                        // reference frame ← current frame
  std::vector<std::pair<int, int>> pairs;  // (index in current, index in reference)
  double rms = 0;                          // m over the pairs after the correction
};

// Unknown-coloured cones pair with any colour; named colours only with the same colour.
std::optional<ConeAlignment> align_cones(const std::vector<Cone>& current, const std::vector<Cone>& reference,
                                         const ConeAlignmentConfig& cfg = {});

}  // namespace fsd::loop_closure
