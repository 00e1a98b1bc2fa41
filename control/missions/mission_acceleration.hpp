#pragma once
// Acceleration and the EBS test: a straight lane fitted to its cones (control/missions/straight_lane.hpp),
// refitted as more of it is seen until the car is well down it. Acceleration times the run from the start line
// to acceleration_length past it, then stops hard; the EBS test asks for Emergency ebs_trigger_distance past the
// start line instead. The lane is driven only as far as it is known to be free: up to the first place the body
// would come near a mapped cone (the braking zone's closing row, however short the zone) and no farther than the
// mapped lane reaches; the speed profile stops within that, braking after its latency, so a short braking zone is
// braked for before the finish line.
#include <cstdint>
#include <optional>

#include "control/missions/mission_run.hpp"

namespace fsd {

class AccelerationMission final : public MissionRun {
 public:
  AccelerationMission(const AutopilotConfig& config, bool ebs_test, ColourConvention convention);

  MissionPath update_path(const MissionInput& in) override;
  MissionEvents progress(const MissionInput& in, const FollowResult* follow) override;
  void limit(const MissionInput& in, ControlCommand& command) const override;
  AsRequest request(const MissionInput& in) override;

  const Path* lane() const { return lane_ ? &*lane_ : nullptr; }
  const Path* drive() const { return drive_ ? &*drive_ : nullptr; }  // the known free part, with speeds
  double start_line_s() const { return start_line_s_; }  // m along the lane to the start line
  double free_s() const { return free_s_; }              // m along the lane clear of cones across it
  double mapped_s() const { return mapped_s_; }          // m along the lane its mapped cones reach

 private:
  // The lane's known free length from the car on, and the path to drive with its speed profile.
  void profile(const MissionInput& in);

  bool ebs_test_;
  ColourConvention convention_;
  std::optional<Path> lane_;   // the fitted centre line, start pose on
  std::optional<Path> drive_;  // its known free part with speeds
  double start_line_s_ = 0;
  double free_s_ = 0;
  double mapped_s_ = 0;
  std::optional<Stamp> timing_start_;  // the car passed the start line
  std::uint64_t cones_seen_ = 0;       // MissionInput::cones_seq of the newest cone map looked at
};

}  // namespace fsd
