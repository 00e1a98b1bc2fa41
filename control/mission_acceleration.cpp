#include "control/mission_acceleration.hpp"

#include <algorithm>
#include <cmath>

#include "control/straight_lane.hpp"

namespace fsd {

AccelerationMission::AccelerationMission(const AutopilotConfig& config, bool ebs_test, ColourConvention convention)
    : MissionRun(config), ebs_test_(ebs_test), convention_(std::move(convention)) {}

MissionPath AccelerationMission::update_path(const MissionInput& in) {
  MissionPath out;
  // The lane is refitted as more of it is seen, until the car is well down it: at speed a refit's sideways jump
  // would only shake the car.
  const bool lane_settled = lane_ && timing_start_ && in.progress_s > start_line_s_ + 30.0;
  if (in.state && in.cones && in.cones_seq != cones_seen_ && !finished() && !lane_settled) {
    cones_seen_ = in.cones_seq;
    const Pose2 origin = started() ? start_pose_ : in.state->pose;
    const double length = 2.0 * config_.mission.acceleration_length + config_.mission.acceleration_stop_distance;
    if (auto line = straight_from_cones(*in.cones, origin, length, config_.planner.ds)) {
      SpeedProfile(config_.speed.known()).apply(*line, 0, config_.speed.v_max);
      line->stamp = in.cones_stamp;
      const auto timing = timing_line_from_cones(*in.cones, origin, convention_);
      const auto foot = timing ? project(*line, timing->mid()) : std::nullopt;
      start_line_s_ = foot ? foot->s : config_.mission.acceleration_start_offset;
      lane_ = std::move(*line);
    }
  }
  out.fixed = lane_.has_value();
  if (in.state && lane_) {
    out.source = PathSource::Straight;
    out.path = &*lane_;
  }
  return out;
}

MissionEvents AccelerationMission::progress(const MissionInput& in, const FollowResult*) {
  MissionEvents out;
  if (!lane_ || !in.state) return out;
  const auto proj = project(*lane_, in.state->pose.position());
  if (!proj) return out;
  const double s = proj->s;
  if (!timing_start_ && s >= start_line_s_) timing_start_ = in.now;
  if (!ebs_test_ && !finished() && s >= start_line_s_ + config_.mission.acceleration_length) {
    out.laps.push_back(LapEvent{1, in.now, in.now - timing_start_.value_or(start_time_)});
    finish(in, config_.mission.acceleration_stop_distance);
  }
  return out;
}

void AccelerationMission::limit(const MissionInput& in, ControlCommand& command) const {
  if (finished())
    command.target_speed = std::min(command.target_speed, stop_cap(in, config_.mission.acceleration_stop_decel));
  // Never faster than the car can stop before a cone across its lane (a short braking zone's closing row):
  // braking zones differ from event to event and the row is only seen from 20 m or so.
  if (!started()) return;
  if (const auto d = cone_across_lane(in)) {
    const double room = *d - config_.mission.lane_end_margin;
    command.target_speed =
        std::min(command.target_speed, room > 0 ? std::sqrt(2.0 * 0.8 * config_.speed.a_brake_max * room) : 0.0);
  }
}

AsRequest AccelerationMission::request(const MissionInput& in) {
  if (!ebs_test_ || !lane_ || !in.state) return AsRequest::None;
  const auto proj = project(*lane_, in.state->pose.position());
  if (!proj || !(proj->s >= start_line_s_ + config_.mission.ebs_trigger_distance)) return AsRequest::None;
  finish(in, config_.mission.acceleration_stop_distance);
  return AsRequest::Emergency;
}

std::optional<double> AccelerationMission::cone_across_lane(const MissionInput& in) const {
  if (!lane_ || !in.state || !in.cones) return std::nullopt;
  const auto car = project(*lane_, in.state->pose.position());
  if (!car) return std::nullopt;
  const double front = config_.planner.tight_turn.body_front;
  const double half_width = config_.planner.tight_turn.body_half_width + 0.3;
  const Vec2 heading(std::cos(in.state->pose.yaw), std::sin(in.state->pose.yaw));
  std::optional<double> nearest;
  for (const auto& c : *in.cones) {
    const Vec2 p = c.position.head<2>();
    const double along = (p - in.state->pose.position()).dot(heading);
    if (along < front || along > 60.0) continue;  // behind the nose, or too far to matter
    const auto proj = project(*lane_, p, car->s, 0.0, 70.0);
    if (!proj || proj->distance() > half_width) continue;
    const double d = proj->s - car->s - front;
    if (d > 0 && (!nearest || d < *nearest)) nearest = d;
  }
  return nearest;
}

}  // namespace fsd
