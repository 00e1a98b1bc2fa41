#pragma once
// The lap's pose graph with cone landmarks (DESIGN.md §5b mapping, issue #17 loop closure): keyframe poses (x, y,
// yaw) chained by the estimator's relative motion between them, cones (x, y) tied to the keyframes they were seen
// from. Until the loop is closed the graph agrees with the estimator exactly; once the car is back at the start and
// a cone seen now is known to be one seen at the start (LoopDetector), the two are one landmark, and the least-
// squares solution (Ceres) spreads the drift accumulated over the lap along it: the odometry's links bend where
// they are weakest (σ grows with the distance between keyframes), the cones follow their keyframes.
//
// A pure core: no clock, no I/O, no thread. The first keyframe is held (it defines the map frame).
#include <cstdint>
#include <map>
#include <vector>

#include "common/geometry.hpp"
#include "common/time.hpp"

namespace fsd::loop_closure {

struct LapGraphConfig {
  double translation_sigma_per_m = 0.01;  // σ of the estimator's relative translation per metre driven ...
  double translation_sigma_min = 0.01;    // m ... and at least this
  double yaw_sigma_per_m = 0.002;         // rad of relative heading per metre driven ...
  double yaw_sigma_min = 0.002;           // rad ... and at least this
  double observation_huber = 0.3;         // m: cone observations beyond it count linearly (a wrong association)
  int max_iterations = 50;
};

struct LapGraphResult {
  bool solved = false;
  std::vector<Pose2> poses;       // per keyframe, map frame
  std::map<int, Vec2> landmarks;  // per landmark id as given to observe() (merged ids share one position)
  double cost_before = 0, cost_after = 0;
  int iterations = 0;
};

class LapGraph {
 public:
  explicit LapGraph(const LapGraphConfig& cfg = {}) : cfg_(cfg) {}
  // A keyframe at the estimator's pose; keyframes come in time order. Returns its index.
  int add_keyframe(Stamp t, const Pose2& estimate);
  // Cone `landmark` seen from keyframe `k` at `in_vehicle` (vehicle frame), with σ per axis. Unknown keyframes are
  // ignored.
  void observe(int k, int landmark, const Vec2& in_vehicle, double sigma);
  // Landmarks `a` and `b` are the same cone (the loop closure's association).
  void same_cone(int a, int b);

  // The optimised graph; with fewer than two keyframes (or nothing to solve) the estimates as they are.
  LapGraphResult optimise() const;

  std::size_t keyframes() const { return keyframes_.size(); }
  std::size_t observations() const { return observations_.size(); }

 private:
  int root(int landmark) const;
  struct Keyframe {
    Stamp t;
    Pose2 estimate;
  };
  struct Observation {
    int k, landmark;
    Vec2 in_vehicle;
    double sigma;
  };
  LapGraphConfig cfg_;
  std::vector<Keyframe> keyframes_;
  std::vector<Observation> observations_;
  std::map<int, int> parent_;  // union-find over landmark ids
};

}  // namespace fsd::loop_closure
