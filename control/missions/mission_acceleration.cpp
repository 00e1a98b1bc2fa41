#include "control/missions/mission_acceleration.hpp"

#include <algorithm>
#include <cmath>

#include "control/missions/straight_lane.hpp"
#include "control/planning/footprint.hpp"

namespace fsd {

namespace {
// Cones this far either side of the lane's centre count as its boundaries (the lane is 3–5 m wide).
constexpr double kLaneReach = 3.5;  // m
}  // namespace

AccelerationMission::AccelerationMission(const AutopilotConfig& config, bool ebs_test, ColourConvention convention)
    : MissionRun(config), ebs_test_(ebs_test), convention_(std::move(convention)) {}

MissionPath AccelerationMission::update_path(const MissionInput& in) {
  MissionPath out;
  if (in.state && in.cones && in.cones_seq != cones_seen_ && !finished()) {
    cones_seen_ = in.cones_seq;
    // The lane is refitted as more of it is seen, until the car is well down it: at speed a refit's sideways jump
    // would only shake the car.
    const bool lane_settled = lane_ && timing_start_ && in.progress_s > start_line_s_ + 30.0;
    const Pose2 origin = started() ? start_pose_ : in.state->pose;
    const double length = 2.0 * config_.mission.acceleration_length + config_.mission.acceleration_stop_distance;
    if (!lane_settled)
      if (auto line = straight_from_cones(*in.cones, origin, length, config_.planner.ds)) {
        line->stamp = in.cones_stamp;
        const auto timing = timing_line_from_cones(*in.cones, origin, convention_);
        const auto foot = timing ? project(*line, timing->mid()) : std::nullopt;
        start_line_s_ = foot ? foot->s : config_.mission.acceleration_start_offset;
        lane_ = std::move(*line);
      }
    if (lane_) profile(in);
  }
  out.fixed = lane_.has_value();
  if (in.state && drive_) {
    out.source = PathSource::Straight;
    out.path = &*drive_;
  }
  return out;
}

void AccelerationMission::profile(const MissionInput& in) {
  const auto car = project(*lane_, in.state->pose.position());
  const double car_s = car ? car->s : 0.0;
  // As far as the mapped lane reaches: the farthest cone beside it ahead of the car.
  double mapped = car_s;
  for (const auto& c : *in.cones) {
    if (!c.position.allFinite()) continue;
    const auto f = project(*lane_, c.position.head<2>(), car_s, 5.0, 200.0);
    if (f && f->distance() <= kLaneReach) mapped = std::max(mapped, f->s);
  }
  // Up to the first place the body would come near a mapped cone (a row across the lane).
  const Body& body = config_.path.body;
  const std::vector<Obstacle> obstacles =
      obstacles_of(*in.cones, config_.path.cone_radius, config_.path.big_cone_radius);
  const SweepResult sweep =
      sweep_body(*lane_, obstacles, body, config_.path.accept_clearance, 0.1, car_s, mapped);
  mapped_s_ = mapped;
  free_s_ = sweep.first_short_s;
  // From standstill at the lane's start (where the car began), to a stop before the first cone across it; the
  // lane's points stay, so that the follower keeps its place on it. (The end of what is mapped moves on with the
  // car: limit() holds the speed to it where the car is, not on the profile the follower previews.)
  if (!drive_ || drive_->stamp != lane_->stamp) drive_ = *lane_;
  SpeedProfile(config_.speed.known()).apply_until(*drive_, 0.0, free_s_);
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
  // Never faster than stops the car with its body inside the mapped lane, braking after the latency.
  if (!lane_ || !in.state) return;
  const auto car = project(*lane_, in.state->pose.position());
  if (!car) return;
  const double room = mapped_s_ - config_.path.body.front - car->s - config_.speed.stop_margin;
  command.target_speed = std::min(command.target_speed, stopping_speed(room, config_.speed.a_brake_max,
                                                                       config_.speed.stop_latency));
}

AsRequest AccelerationMission::request(const MissionInput& in) {
  if (!ebs_test_ || !lane_ || !in.state) return AsRequest::None;
  const auto proj = project(*lane_, in.state->pose.position());
  if (!proj || !(proj->s >= start_line_s_ + config_.mission.ebs_trigger_distance)) return AsRequest::None;
  finish(in, config_.mission.acceleration_stop_distance);
  return AsRequest::Emergency;
}

}  // namespace fsd
