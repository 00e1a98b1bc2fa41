#pragma once
// Skid pad: a straight entry lane from the start pose until the circles are fitted (control/skidpad.hpp), then
// the figure of eight (right circle twice, left circle twice, exit), refitted while the car is still on the entry
// lane. A lap is one circle, timed crossing to crossing; the fourth ends the mission.
#include <cstdint>
#include <optional>

#include "control/mission_run.hpp"
#include "control/skidpad.hpp"

namespace fsd {

class SkidpadMission final : public MissionRun {
 public:
  SkidpadMission(const AutopilotConfig& config, ColourConvention convention);

  MissionPath update_path(const MissionInput& in) override;
  MissionEvents progress(const MissionInput& in, const FollowResult* follow) override;

  const std::optional<SkidpadGeometry>& geometry() const { return geometry_; }
  const SkidpadPlan* plan() const { return plan_ ? &*plan_ : nullptr; }

 private:
  ColourConvention convention_;
  std::optional<Path> entry_;  // straight on from the start pose until the circles are fitted
  std::optional<SkidpadGeometry> geometry_;
  std::optional<SkidpadPlan> plan_;
  int crossings_ = 0;  // of plan_->crossing_s passed
  std::optional<Stamp> last_crossing_;
  std::uint64_t cones_seen_ = 0;  // MissionInput::cones_seq of the newest cone map looked at
};

}  // namespace fsd
