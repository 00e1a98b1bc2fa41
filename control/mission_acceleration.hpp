#pragma once
// Acceleration and the EBS test: a straight lane fitted to its cones (control/straight_lane.hpp),
// refitted as more of it is seen until the car is well down it. Acceleration times the run from the start line
// to acceleration_length past it, then stops hard; the EBS test asks for Emergency ebs_trigger_distance past the
// start line instead. On the lane the speed never exceeds what stops the car short of a cone across it (the
// braking zone's closing row, however short the zone).
#include <cstdint>
#include <optional>

#include "control/mission_run.hpp"

namespace fsd {

class AccelerationMission final : public MissionRun {
 public:
  AccelerationMission(const AutopilotConfig& config, bool ebs_test, ColourConvention convention);

  MissionPath update_path(const MissionInput& in) override;
  MissionEvents progress(const MissionInput& in, const FollowResult* follow) override;
  void limit(const MissionInput& in, ControlCommand& command) const override;
  AsRequest request(const MissionInput& in) override;

  const Path* lane() const { return lane_ ? &*lane_ : nullptr; }
  double start_line_s() const { return start_line_s_; }  // m along the lane to the start line
  // Metres from the nose to the nearest cone across the lane ahead (within the car's width and a margin of the
  // line): the braking zone's closing row, once seen.
  std::optional<double> cone_across_lane(const MissionInput& in) const;

 private:
  bool ebs_test_;
  ColourConvention convention_;
  std::optional<Path> lane_;
  double start_line_s_ = 0;
  std::optional<Stamp> timing_start_;  // the car passed the start line
  std::uint64_t cones_seen_ = 0;       // MissionInput::cones_seq of the newest cone map looked at
};

}  // namespace fsd
