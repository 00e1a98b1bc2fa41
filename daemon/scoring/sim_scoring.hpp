#pragma once
// The scorecard of a run on the virtual car (daemon/scoring/scorecard.hpp), as `fsd run --sim` and the replay of its
// recording both fill it: one Scorecard for the track and mission, fed the simulator's truth each cycle (the
// car's true state, the standing cones), the Stack's detections scored against the truth at their instant, and at
// the end the Stack's latencies, faults, cone map and perception figures. The live run feeds the virtual car's
// truth; the replay the recorded truth frames (RawChannel::TruthState / TruthCones / TruthLidarReturns), so both
// score alike.
#include <memory>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/track.hpp"
#include "common/types.hpp"
#include "daemon/scoring/lidar_visibility.hpp"
#include "daemon/scoring/odometry_score.hpp"
#include "daemon/scoring/perception_score.hpp"
#include "daemon/scoring/scorecard.hpp"
#include "daemon/stack/loop_closure_record.hpp"
#include "daemon/stack/settings.hpp"
#include "drivers/sim/vehicle/vehicle_truth.hpp"
#include "localization/pose_history.hpp"

namespace fsd {

class Stack;

// The stop zone after a mission's last timing line (m).
double stop_zone(Mission m);

// The virtual car's true state as the Stack's VehicleState, and back (what a truth frame carries).
VehicleState state_from_truth(const sim::VehicleTruth& t);
sim::VehicleTruth truth_from_state(const VehicleState& s);

class SimScoring {
 public:
  // Registers the Stack's detections hook; `stack` must outlive this.
  SimScoring(const Track& track, Mission mission, const RunSettings& run, Stack& stack);

  // Each cycle, before the Stack steps: the car's true state (monotonic time).
  void on_truth(const sim::VehicleTruth& truth);
  // The standing cones, whenever they change (a cone knocked over), as the Stack is sent them.
  void set_truth_cones(std::vector<Cone> cones) { truth_cones_ = std::move(cones); }
  // The returns the simulated LiDAR sent from each cone since the last call (which cones it could see).
  void add_lidar_returns(const std::vector<TruthLidarReturns>& returns) { visibility_.add(returns); }
  // After the step: the VCU's true AS state and the cones hit so far; the Stack's pose against the truth; the
  // cone map as it is when lap 1 is timed ("map_lap1": the map lap 2 drives on, before lap 2's sightings).
  void after_step(AsState as, int cones_hit);
  // The end of the run: wall time, the Stack's latencies and faults, the "map", "map_lap1" and "perception"
  // sections.
  void finish(double wall_time_s);

  Scorecard& card() { return *card_; }
  const Scorecard& card() const { return *card_; }

 private:
  const Track& track_;
  RunSettings run_;
  Stack& stack_;
  std::unique_ptr<Scorecard> card_;
  PerceptionScore perception_;
  LidarVisibility visibility_;
  OdometryScore odometry_;
  PoseHistory truth_poses_{256};  // the car's true poses of the last 2.5 s, for the perception score
  // A loop closure is scored when its solve comes back, which on a worker (--workers) is seconds of simulated time
  // later when the simulation runs fast: its truth from a coarser history of the last two minutes (20 Hz).
  PoseHistory truth_track_{2400};
  Pose2 last_pose_;
  std::vector<Cone> truth_cones_;
  struct ClosureScore {
    LoopClosureRecord record;
    double error_before = 0, error_after = 0;  // m from the true pose at its instant; NaN: not known
  };
  std::vector<ClosureScore> loop_closures_;  // the odometry section's
  nlohmann::json map_lap1_;                  // the "map_lap1" section, once lap 1 is timed
};

}  // namespace fsd
