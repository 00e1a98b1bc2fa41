#pragma once
// Loop closure for a drifting estimator (DESIGN.md §5b mapping, issue #17): fed each perception frame (its instant,
// the estimator's pose then, the cones seen in the vehicle frame), it builds the lap's pose graph (LapGraph:
// keyframes every `keyframe_spacing` metres, the cones as landmarks) and remembers the scene around the start (the
// cones first seen in the first `start_distance` metres, the start line's big orange cones among them). Once the
// car has driven `min_lap_distance` on this lap and its estimate is back within `near_start` of the start, the cones
// seen in the last metres are aligned against the start's (align_cones); with enough unambiguous pairs those are
// tied as the same cones and the graph is solved: the loop's event carries the correction of the newest pose (map
// ← estimated) and the lap's optimised keyframes, so that the caller can move its pose, map and recorded lap.
// Then the next lap's graph starts at the corrected pose, with the start's scene (now in the map frame) held.
//
// The solve (110–410 ms) may run elsewhere: feed() does the cheap part and hands out the lap's LoopSolve; frames fed
// while it is out are held, and finish() takes its result, starts the next lap at the corrected pose and replays
// the held frames moved by the correction, so that the next lap is what it would have been had the solve taken no
// time. add() is both at once.
//
// A sighting joins a landmark of this lap seen within the last `live_distance` metres; a cone seen at the start
// and again at the lap's end is therefore two landmarks until the loop ties them, whatever the drift.
//
// A pure core: no clock, no I/O, no thread (Ceres runs on whichever thread runs solve_loop).
#include <array>
#include <optional>
#include <vector>

#include "common/types.hpp"
#include "localization/loop_closure/cone_alignment.hpp"
#include "localization/loop_closure/lap_graph.hpp"
#include "localization/loop_closure/loop_solve.hpp"

namespace fsd::loop_closure {

struct LoopCloserConfig {
  bool enabled = true;
  double keyframe_spacing = 1.0;    // m driven between keyframes (frames in between are skipped)
  double start_distance = 10.0;     // m: cones first seen this early in the run form the start's scene
  double min_lap_distance = 100.0;  // m driven on a lap before its loop may close
  double near_start = 30.0;         // m: back at the start: within the perception range and the start scene
  double recent_distance = 20.0;    // m: the scene now is the landmarks seen within the last this many metres
  double live_distance = 30.0;      // m: a landmark not seen for this long takes no more sightings
  double association_gate = 0.7;    // m: a sighting this close to a live landmark is that cone
  double max_range = 20.0;          // m: farther sightings are left out
  double sighting_sigma = 0.1;      // m per axis, a cone's position in the vehicle frame
  int min_sightings = 2;            // a landmark seen fewer times is not part of a scene
  ConeAlignmentConfig alignment{.min_pairs = 6};
  LapGraphConfig graph;
};

class LoopCloser {
 public:
  explicit LoopCloser(const LoopCloserConfig& cfg = {}) : cfg_(cfg) {}

  // One perception frame, in time order: the estimated pose at `t` (map frame, as corrected by the closures taken
  // so far) and the cones seen (vehicle frame). Returns the lap's loop to solve when this frame closes it; while
  // that solve is out (solving()) the frames are held for finish().
  std::optional<LoopSolve> feed(Stamp t, const Pose2& estimate, const std::vector<Cone>& seen);
  // The result of the solve feed() handed out: the loop's closure, the next lap started at the corrected pose and
  // the held frames replayed moved by the correction (their poses were estimated before it). Nullopt when the solve
  // failed: the lap goes on, its held frames replayed as they were, and the next keyframe tries again.
  std::optional<LoopClosure> finish(const LoopSolveResult& r);
  bool solving() const { return solving_; }

  // feed() and the solve at once, on the caller's thread. Returns the loop's closure when this frame closes it.
  std::optional<LoopClosure> add(Stamp t, const Pose2& estimate, const std::vector<Cone>& seen);

  int laps_closed() const { return laps_closed_; }
  double lap_distance() const { return odometer_ - lap_start_odometer_; }  // m driven on the current lap
  std::size_t keyframes() const { return graph_.keyframes(); }
  const std::vector<Cone>& start_scene() const { return start_scene_; }  // map frame, after the first closure

 private:
  struct Landmark {
    Vec2 sum = Vec2::Zero();  // of the placed sightings
    int n = 0;
    double first_seen = 0, last_seen = 0;  // odometer
    std::array<int, 6> votes{};
    bool reference = false;  // the start's scene (this lap's part of the graph to close against)
    Cone cone(int id) const;
  };
  struct Frame {
    Stamp t;
    Pose2 estimate;
    std::vector<Cone> seen;
  };
  std::optional<LoopSolve> take(Stamp t, const Pose2& estimate, const std::vector<Cone>& seen, bool may_close);
  void start_lap(Stamp t, const Pose2& pose);
  void observe(int k, const Pose2& pose, const std::vector<Cone>& seen);
  std::optional<LoopSolve> try_close();

  LoopCloserConfig cfg_;
  LapGraph graph_;
  std::vector<Landmark> landmarks_;  // this lap's, by id
  std::vector<Pose2> estimates_;     // this lap's keyframes, as given
  std::vector<Stamp> stamps_;
  std::optional<Pose2> start_pose_, last_pose_;
  std::vector<Cone> start_scene_;  // the start's cones in the map frame (ids: this lap's landmarks of them)
  double odometer_ = 0, lap_start_odometer_ = 0;
  int laps_closed_ = 0;
  bool solving_ = false;
  std::vector<Frame> held_;  // fed while solving (a solve's time: a few frames)
};

}  // namespace fsd::loop_closure
