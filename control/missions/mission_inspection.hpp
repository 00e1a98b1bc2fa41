#pragma once
// Inspection: the car on its jacks sweeps the steering (a sine of inspection_amplitude of the lock, period
// inspection_period) with the wheels turning slowly, for inspection_duration, then finishes. No path, no cones:
// the supervisor does not watch perception or planning.
#include "control/missions/mission_run.hpp"

namespace fsd {

class InspectionMission final : public MissionRun {
 public:
  using MissionRun::MissionRun;

  bool needs_perception() const override { return false; }
  MissionPath update_path(const MissionInput&) override { return {}; }
  MissionEvents progress(const MissionInput& in, const FollowResult* follow) override;
  // The sweep replaces the follower's command.
  void limit(const MissionInput& in, ControlCommand& command) const override;
};

}  // namespace fsd
