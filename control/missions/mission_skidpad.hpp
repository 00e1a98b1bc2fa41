#pragma once
// Skid pad: a straight entry lane from the start pose until the circles are fitted (control/missions/skidpad.hpp), then
// the figure of eight (right circle twice, left circle twice, exit), refitted while the car is still on the entry
// lane. A lap is one circle, timed crossing to crossing; the fourth ends the mission. The figure of eight is driven
// only as far as it is known to be free: it stops before the first place the body would come near a mapped cone
// (the row that closes the exit lane).
#include <cstdint>
#include <optional>

#include "control/missions/mission_run.hpp"
#include "control/missions/skidpad.hpp"
#include "control/planning/speed_profile.hpp"

namespace fsd {

class SkidpadMission final : public MissionRun {
 public:
  SkidpadMission(const AutopilotConfig& config, ColourConvention convention);

  MissionPath update_path(const MissionInput& in) override;
  MissionEvents progress(const MissionInput& in, const FollowResult* follow) override;

  const std::optional<SkidpadGeometry>& geometry() const { return geometry_; }
  const SkidpadPlan* plan() const { return plan_ ? &*plan_ : nullptr; }

 private:
  SpeedLimits limits() const;
  // drive_: the plan's path cut before the first place its body would come near a mapped cone, profiled.
  void cut_to_free(const MissionInput& in);

  ColourConvention convention_;
  std::optional<Path> entry_;  // straight on from the start pose until the circles are fitted
  std::optional<SkidpadGeometry> geometry_;
  std::optional<SkidpadPlan> plan_;
  std::optional<Path> drive_;  // plan_'s path up to where it is known to be free, with speeds
  double plan_speed_ = 0;      // m/s of the car when the plan was made (its profile starts there)
  int crossings_ = 0;  // of plan_->crossing_s passed
  std::optional<Stamp> last_crossing_;
  std::uint64_t cones_seen_ = 0;  // MissionInput::cones_seq of the newest cone map looked at
};

}  // namespace fsd
