#include "control/missions/mission_inspection.hpp"

#include <cmath>
#include <numbers>

namespace fsd {

MissionEvents InspectionMission::progress(const MissionInput& in, const FollowResult*) {
  if (in.now - start_time_ >= config_.mission.inspection_duration) finish(in, config_.mission.stop_distance);
  return {};
}

void InspectionMission::limit(const MissionInput& in, ControlCommand& command) const {
  const double t = in.now - start_time_;
  const double amplitude = config_.mission.inspection_amplitude * config_.follower.max_steer;
  command.steering = started() ? amplitude * std::sin(2 * std::numbers::pi * t / config_.mission.inspection_period) : 0;
  command.target_speed = finished() ? 0.0 : config_.mission.inspection_speed;
}

}  // namespace fsd
