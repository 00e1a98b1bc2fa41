#include "control/autopilot.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "control/missions/mission_acceleration.hpp"
#include "control/missions/mission_inspection.hpp"
#include "control/missions/mission_skidpad.hpp"
#include "control/missions/mission_trackdrive.hpp"

namespace fsd {

Autopilot::Autopilot(AutopilotConfig config, Mission mission, ColourConvention convention)
    : config_(config),
      mission_(mission),
      planner_(config.planner, config.path, convention, config.speed.realtime()),
      guard_(config.guard),
      follower_(config.follower),
      lap2_follower_(config.lap2.follower(config.follower)),
      supervisor_(config.supervisor) {
  run_ = make_run(mission, convention);
  supervisor_.set_mission(mission);
  supervisor_.require(InputStream::Lidar, run_->needs_perception());
  supervisor_.require(InputStream::Plan, run_->needs_perception());
}

std::unique_ptr<MissionRun> Autopilot::make_run(Mission mission, const ColourConvention& convention) {
  switch (mission) {
    case Mission::Trackdrive:
    case Mission::Autocross: {
      auto run = std::make_unique<TrackdriveMission>(config_, mission, convention);
      trackdrive_ = run.get();
      return run;
    }
    case Mission::Acceleration:
    case Mission::EbsTest:
      return std::make_unique<AccelerationMission>(config_, mission == Mission::EbsTest, convention);
    case Mission::Skidpad: {
      auto run = std::make_unique<SkidpadMission>(config_, convention);
      skidpad_run_ = run.get();
      return run;
    }
    case Mission::Inspection:
      return std::make_unique<InspectionMission>(config_);
    case Mission::None:
      break;
  }
  return std::make_unique<NoMission>(config_);
}

const Path* Autopilot::recorded_path() const { return trackdrive_ ? trackdrive_->lap_path() : nullptr; }

const std::optional<SkidpadGeometry>& Autopilot::skidpad() const {
  static const std::optional<SkidpadGeometry> none;
  return skidpad_run_ ? skidpad_run_->geometry() : none;
}

bool Autopilot::open_end_seen() const { return trackdrive_ && trackdrive_->open_end_seen(); }

void Autopilot::set_lap_builder(LapBuildService* service) {
  if (trackdrive_) trackdrive_->set_lap_builder(service);
}

void Autopilot::set_config(const AutopilotConfig& config) {
  config_ = config;
  planner_.set_config(config.planner, config.path);
  guard_.set_config(config.guard);
  planner_.set_speed_limits(config.speed.realtime());
  follower_.set_config(config.follower);
  lap2_follower_.set_config(config.lap2.follower(config.follower));
  supervisor_.set_config(config.supervisor);
  run_->set_config(config);
}

void Autopilot::on_vcu(const VcuStatus& status) { supervisor_.on_vcu(status); }

void Autopilot::on_cones(Stamp t, std::vector<Cone> map_cones) {
  if (!std::isfinite(t)) return;
  cones_ = std::move(map_cones);
  obstacles_ = obstacles_of(cones_, config_.path.cone_radius, config_.path.big_cone_radius);
  ++cones_seq_;
  if (cones_stamp_ < 0 || t - cones_stamp_ > config_.supervisor.lidar_timeout) cones_unbroken_since_ = t;
  cones_stamp_ = t;
  new_cones_ = true;
  supervisor_.heartbeat(InputStream::Lidar, t);
}

void Autopilot::on_state(const VehicleState& state) {
  if (!std::isfinite(state.stamp) || !std::isfinite(state.pose.x) || !std::isfinite(state.pose.y) ||
      !std::isfinite(state.pose.yaw))
    return;
  state_ = state;
  supervisor_.heartbeat(InputStream::Pose, state.stamp);
}

void Autopilot::on_camera(Stamp t) {
  if (std::isfinite(t)) supervisor_.heartbeat(InputStream::Camera, t);
}

void Autopilot::on_gnss(Stamp t, bool good) {
  if (!std::isfinite(t)) return;
  gnss_good_ = good;
  if (good) {
    gnss_good_since_ = t;
    supervisor_.heartbeat(InputStream::Gnss, t);
  }
}

void Autopilot::on_map_match(Stamp t) {
  if (std::isfinite(t)) map_matched_ = t;
}

void Autopilot::relocate(const std::function<Pose2(Stamp)>& correction, Stamp now) {
  if (state_) state_->pose = correction(state_->stamp) * state_->pose;
  // Moved with the pose, so that the correction is no distance driven.
  if (last_position_) last_position_ = correction(now).transform(*last_position_);
  if (plan_) transform_path(*plan_, correction(plan_->stamp));
  if (plan_pending_) discard_plan_ = true;  // planned on the map before the correction
  run_->relocate(correction, now);
}

bool Autopilot::plan(Stamp now) {
  plan_outcome_ = {};
  if (!run_->uses_planner() || !state_ || planner_stalled_) return false;
  bool taken = false;
  if (plan_pending_) {
    if (auto r = plan_service_->poll()) {
      plan_pending_ = false;
      if (!std::exchange(discard_plan_, false)) {
        take_plan(now, std::move(*r));
        taken = true;
      }
    }
  }
  if (plan_pending_ || (!new_cones_ && now - last_plan_attempt_ < config_.replan_period)) return taken;
  new_cones_ = false;
  last_plan_attempt_ = now;
  if (plan_service_) {
    // The job gets copies: the map and the state move on meanwhile.
    PlanJob job = [planner = planner_, cones = cones_, state = *state_, previous = plan_] {
      return planner.plan(cones, state, previous ? &*previous : nullptr);
    };
    if (plan_service_->submit(std::move(job))) {
      plan_pending_ = true;
      return taken;
    }
  }
  take_plan(now, planner_.plan(cones_, *state_, plan_ ? &*plan_ : nullptr));
  return true;
}

void Autopilot::take_plan(Stamp now, PlanResult r) {
  plan_outcome_ = {true, r.ok, r.single_boundary, r.ignored_colours, r.cut_short};
  // A plan that fails or ends short says why; a stop for want of a plan, or for standing still, names it.
  supervisor_.on_plan(now, r.ok, r.reason);
  if (r.ok) plan_ = std::move(r.path);
}

MissionInput Autopilot::mission_input(Stamp now, bool plan_ok) const {
  MissionInput in;
  in.now = now;
  in.state = state_ ? &*state_ : nullptr;
  in.cones = &cones_;
  in.cones_seq = cones_seq_;
  in.cones_stamp = cones_stamp_;
  in.cones_unbroken_since = cones_unbroken_since_;
  in.plan = plan_ ? &*plan_ : nullptr;
  in.plan_ok = plan_ok;
  in.gnss_ok = gnss_good_ && gnss_good_since_ && now - *gnss_good_since_ <= config_.gnss_timeout;
  in.gnss_seen = gnss_good_since_.has_value();
  in.map_matched = map_matched_ && now - *map_matched_ <= config_.map_match_timeout;
  in.odometer = odometer_;
  in.progress_s = progress_s_;
  return in;
}

void Autopilot::report(Stamp now, const std::vector<MissionFault>& faults) {
  for (const auto& f : faults) supervisor_.report(now, f.source, f.what, f.action, f.active);
}

ControlOutput Autopilot::step(Stamp now) {
  ControlOutput out;
  out.command.stamp = now;
  out.planned = plan_outcome_.planned;
  out.plan_ok = plan_outcome_.ok;
  out.plan_one_boundary = plan_outcome_.one_boundary;
  out.plan_colour_blind = plan_outcome_.colour_blind;
  out.plan_cut_short = plan_outcome_.cut_short;
  plan_outcome_ = {};
  const double speed = state_ ? std::max(0.0, state_->speed()) : 0.0;
  if (state_) {
    const Vec2 p = state_->pose.position();
    if (last_position_) odometer_ += (p - *last_position_).norm();
    last_position_ = p;
  }
  const bool driving = supervisor_.as_state() == AsState::Driving;
  MissionInput in = mission_input(now, out.plan_ok);
  if (driving && !run_->started() && state_) {
    run_->start(in);
    follower_.reset();
  }

  // The mission's path: the real-time plan (plan()), the recorded lap, a lane, a skid pad's figure of eight.
  const MissionPath mission_path = run_->update_path(in);
  // The mission's own paths count as plans for the watchdog while they exist.
  if (mission_path.fixed) supervisor_.heartbeat(InputStream::Plan, now);
  report(now, mission_path.faults);

  // Follow it.
  const PathSource source = state_ ? mission_path.source : PathSource::None;
  const Path* path = state_ ? mission_path.path : nullptr;
  // The recorded lap has a follower of its own (control.lap2 gains); every other path the real-time one.
  PathFollower& f = source == PathSource::Recorded ? lap2_follower_ : follower_;
  // Back on a path after another one (GNSS regained): the follower's projection hint is from long ago. A mission
  // path that replaces the one followed says where on it the car is: a figure of eight passes its crossing five
  // times, and the nearest point of it all may be another pass.
  if (source != last_source_) f.reset();
  if (mission_path.replaced) follower_.reset(mission_path.resume_s);
  FollowResult follow;
  if (path && state_) {
    follow = f.follow(*path, *state_, now, config_.speed.v_max);
    if (follow.ok) progress_s_ = follow.s;
  }
  in.progress_s = progress_s_;
  if (driving && run_->started() && state_) {
    const MissionEvents events = run_->progress(in, path ? &follow : nullptr);
    for (const auto& lap : events.laps) {
      lap_times_.push_back(lap.time_s);
      out.lap = lap;
    }
    if (events.lap_line) {
      lap2_follower_.reset();
      out.lap_line = events.lap_line;
    }
    report(now, events.faults);
  }

  // The follower's command within the car's top speed and the mission's limits (the stop after its finish, ...).
  ControlCommand cmd = follow.command;
  cmd.stamp = now;
  cmd.target_speed = std::min(cmd.target_speed, config_.speed.v_max);
  run_->limit(in, cmd);
  // The contact guard: the car's predicted motion against the mapped cones; a predicted contact slows it first.
  if (path && state_ && follow.ok) {
    out.guard = guard_.check(*path, f, *state_, cmd, obstacles_, config_.path.body, config_.follower.wheelbase,
                             config_.follower.max_steer);
    if (out.guard.contact) cmd.target_speed = std::min(cmd.target_speed, out.guard.speed_cap);
  }
  supervisor_.report(now, "guard", "contact with a cone predicted", "slowing to stop short of it", out.guard.contact);

  // Supervision: no motion outside Driving, controlled stop on faults, Ready/Finished/Emergency requests.
  const Supervision sup = supervisor_.evaluate(now, speed, run_->finished());
  out.request = sup.request;
  if (driving && state_) {
    if (const AsRequest r = run_->request(in); r != AsRequest::None) out.request = r;  // the EBS test's trigger
  }
  supervisor_.requested(out.request);
  if (sup.may_move) {
    cmd.target_speed = std::clamp(std::min(cmd.target_speed, sup.speed_cap), 0.0, config_.speed.v_max);
    cmd.brake_hard = false;
  } else if (sup.controlled_stop) {
    cmd.target_speed = 0;
    cmd.brake_hard = true;
    if (!follow.ok) cmd.steering = last_steering_;  // no pose or off the path: hold the wheel
  } else {
    cmd.target_speed = 0;
    cmd.steering = 0;
    cmd.brake_hard = false;
  }
  if (!std::isfinite(cmd.steering)) cmd.steering = 0;
  last_steering_ = cmd.steering;
  out.command = cmd;
  out.source = source;
  last_source_ = source;
  out.path = path;
  out.follow = follow;
  out.finished = run_->finished();
  out.stopping = supervisor_.stopping();
  return out;
}

}  // namespace fsd
