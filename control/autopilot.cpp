#include "control/autopilot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

namespace fsd {

std::string to_string(const LapLineBuilt& l) {
  char buf[200];
  std::snprintf(
      buf, sizeof buf,
      "lap path built: %.1f m, closed within %.2f m, moved %.2f m (RMS) onto the centre line, %d tight turn(s)",
      l.length, l.closure_gap, l.recentre_rms, l.tight_turns);
  return buf;
}

std::string_view to_string(PathSource s) {
  switch (s) {
    case PathSource::None:
      return "none";
    case PathSource::Planner:
      return "planner";
    case PathSource::Recorded:
      return "recorded";
    case PathSource::Skidpad:
      return "skidpad";
    case PathSource::Straight:
      return "straight";
  }
  return "none";
}

Autopilot::Autopilot(AutopilotConfig config, Mission mission, ColourConvention convention)
    : config_(config),
      mission_(mission),
      convention_(convention),
      planner_(config.planner, convention, config.speed.realtime()),
      follower_(config.follower),
      lap2_follower_(config.lap2.follower(config.follower)),
      supervisor_(config.supervisor),
      trajectory_(config.trajectory) {
  supervisor_.set_mission(mission);
  const bool inspection = mission == Mission::Inspection;
  supervisor_.require(InputStream::Lidar, !inspection);
  supervisor_.require(InputStream::Plan, !inspection);
}

void Autopilot::set_config(const AutopilotConfig& config) {
  config_ = config;
  planner_.set_config(config.planner);
  planner_.set_speed_limits(config.speed.realtime());
  follower_.set_config(config.follower);
  lap2_follower_.set_config(config.lap2.follower(config.follower));
  supervisor_.set_config(config.supervisor);
  // The stored lap's speeds follow the car's limits (μ, lap 2's share, v_max) as they are tuned, with the caps of
  // its tight turns.
  if (lap_path_) SpeedProfile(lap2_limits()).apply(*lap_path_, 0, 0, lap_zones_);
}

void Autopilot::on_vcu(const VcuStatus& status) { supervisor_.on_vcu(status); }

void Autopilot::on_cones(Stamp t, std::vector<Cone> map_cones) {
  if (!std::isfinite(t)) return;
  cones_ = std::move(map_cones);
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

void Autopilot::on_gnss(Stamp t, bool good) {
  if (!std::isfinite(t)) return;
  gnss_good_ = good;
  if (good) {
    gnss_good_since_ = t;
    supervisor_.heartbeat(InputStream::Gnss, t);
  }
}

namespace {
LapLineBuilt summary(const TrajectoryResult& r) {
  return {r.path ? r.path->length() : 0.0, r.closure_gap, r.recentre_rms, static_cast<int>(r.zones.size())};
}
}  // namespace

bool Autopilot::plan(Stamp now) {
  plan_outcome_ = {};
  if (!uses_planner() || !state_ || planner_stalled_) return false;
  if (!new_cones_ && now - last_plan_attempt_ < config_.replan_period) return false;
  new_cones_ = false;
  last_plan_attempt_ = now;
  PlanResult r = planner_.plan(cones_, *state_);
  plan_outcome_ = {true, r.ok, r.single_boundary, r.ignored_colours, r.tight_turn.has_value()};
  supervisor_.on_plan(now, r.ok);
  if (r.ok) plan_ = std::move(r.path);
  return true;
}

void Autopilot::start_mission(Stamp now) {
  started_ = true;
  mission_start_ = now;
  start_pose_ = state_->pose;
  follower_.reset();
  if (uses_planner()) {
    const auto line = timing_line_from_cones(cones_, start_pose_, convention_);
    lap_counter_.emplace(line ? *line : line_across(start_pose_), config_.laps);
    // A layout whose start pose is past the line (and close to it) times the first lap from the start.
    const double past = lap_counter_->line().past(start_pose_.position());
    if (past > 0 && past < config_.laps.hysteresis) {
      lap_counter_->start_timing_at(now);
      lap1_start_ = now;
    }
  }
}

void Autopilot::finish(Stamp now) {
  if (finished_) return;
  finished_ = true;
  finish_speed_ = state_ ? state_->speed() : 0.0;
  finish_odometer_ = odometer_;
  stop_distance_ = mission_ == Mission::Acceleration || mission_ == Mission::EbsTest
                       ? config_.mission.acceleration_stop_distance
                       : config_.mission.stop_distance;
  (void)now;
}

std::optional<double> Autopilot::cone_across_straight() const {
  if (!straight_ || !state_) return std::nullopt;
  const auto car = project(*straight_, state_->pose.position());
  if (!car) return std::nullopt;
  const double front = config_.planner.tight_turn.body_front;
  const double half_width = config_.planner.tight_turn.body_half_width + 0.3;
  std::optional<double> nearest;
  for (const auto& c : cones_) {
    const Vec2 p = c.position.head<2>();
    const double along =
        (p - state_->pose.position()).dot(Vec2(std::cos(state_->pose.yaw), std::sin(state_->pose.yaw)));
    if (along < front || along > 60.0) continue;  // behind the nose, or too far to matter
    const auto proj = project(*straight_, p, car->s, 0.0, 70.0);
    if (!proj || proj->distance() > half_width) continue;
    const double d = proj->s - car->s - front;
    if (d > 0 && (!nearest || d < *nearest)) nearest = d;
  }
  return nearest;
}

void Autopilot::detect_open_end(Stamp now) {
  // Only the first time round on real-time plans: a loop's recorded lap never ends.
  if (run_out_ || finished_ || !plan_ || !state_ || plan_->points.size() < 2 || !lap_counter_ ||
      lap_counter_->laps_completed() > 0 || config_.mission.open_end_sight <= 0 ||
      odometer_ < config_.mission.open_end_min_travel)
    return;
  // Only on a fresh view: with the sensors silent, no cones beyond the plan proves nothing; nor just after a gap,
  // while the map has not yet confirmed the cones that came into range meanwhile.
  if (now - cones_stamp_ > 0.3 || now - cones_unbroken_since_ < config_.mission.open_end_settle) return;
  const PathPoint& end = plan_->points.back();
  const Vec2 dir(std::cos(end.yaw), std::sin(end.yaw));
  // The walk stopped well inside what the sensors see: if the track went on, its next cones (≤ 5 m apart by the
  // rules) would be mapped beyond the last crossing.
  if ((end.p - state_->pose.position()).norm() > config_.mission.open_end_sight) return;
  const TimingLine& line = lap_counter_->line();
  if ((end.p - line.mid()).norm() < config_.laps.hysteresis && dir.dot(line.forward) > 0.5) return;  // loop closing
  for (const auto& c : cones_) {
    if (!c.position.allFinite()) continue;
    const Vec2 d = c.position.head<2>() - end.p;
    if (d.dot(dir) > 1.0 && d.norm() < 10.0) return;
  }
  Path out = *plan_;
  out.closed = false;
  open_end_s_ = out.length();
  const double ds = std::max(0.05, config_.planner.ds);
  for (double s = ds; s <= config_.mission.stop_distance + 1e-9; s += ds)
    out.points.push_back({end.p + s * dir, 0, 0, 0, 0});
  compute_geometry(out);
  SpeedProfile(config_.speed.realtime()).apply(out, std::max(0.0, state_->speed()), 0.0);
  run_out_ = std::move(out);
  follower_.reset();
}

void Autopilot::update_mission(Stamp now, const FollowResult* last_follow, ControlOutput& out) {
  const VehicleState& st = *state_;
  const Vec2 pos = st.pose.position();
  switch (mission_) {
    case Mission::Trackdrive:
    case Mission::Autocross: {
      take_lap_build(now, out);
      const bool was_timing = lap_counter_->timing();
      const auto ev = lap_counter_->update(now, pos);
      if (!was_timing && lap_counter_->timing() && !lap1_start_) lap1_start_ = lap_counter_->last_crossing();
      if (lap_counter_->laps_completed() == 0) trajectory_.record(st);
      // An open layout ends at its last cones: one run, timed from the start of the mission.
      if (run_out_ && !finished_ && last_follow && last_follow->ok && last_follow->s >= open_end_s_) {
        const double t = now - lap1_start_.value_or(mission_start_);
        lap_times_.push_back(t);
        out.lap = LapEvent{1, now, t};
        finish(now);
        break;
      }
      // Shortly before the end of lap 1, close the lap with the plan ahead and take it: the car then crosses the
      // line at the lap's speed, so lap 2 is a flying lap.
      const double early = config_.trajectory.early_build_distance;
      if (!lap_path_ && !build_pending_ && !ev && early > 0 && target_laps() > 1 &&
          lap_counter_->laps_completed() == 0 && lap_counter_->timing() && plan_ &&
          odometer_ > config_.trajectory.min_lap_length) {
        const TimingLine& line = lap_counter_->line();
        const double before = -line.past(pos);
        const bool across = std::abs((pos - line.mid()).dot(Vec2(-line.forward.y(), line.forward.x()))) <
                            0.5 * (line.b - line.a).norm() + config_.laps.line_margin;
        const Vec2 heading(std::cos(st.pose.yaw), std::sin(st.pose.yaw));
        if (before > 0 && before < early && across && heading.dot(line.forward) > 0.7) {
          std::vector<Vec2> ahead;
          for (const auto& q : plan_->points) ahead.push_back(q.p);
          pending_early_ = true;
          build_lap(now, now, std::move(ahead), out);
        }
      }
      if (ev) {
        lap_times_.push_back(ev->time_s);
        out.lap = ev;
        if (ev->lap == 1) lap1_end_ = ev->t;
        // No lap path yet: built to the line now, unless the early build is still under way (should that one
        // fail, this one follows).
        if (ev->lap == 1 && target_laps() > 1 && !lap_path_ && !build_pending_) {
          pending_early_ = false;
          build_lap(now, ev->t, {}, out);
        }
        if (ev->lap >= target_laps()) finish(now);
      }
      break;
    }
    case Mission::Acceleration:
    case Mission::EbsTest: {
      if (!straight_) break;
      const auto proj = project(*straight_, pos);
      if (!proj) break;
      const double s = proj->s;
      if (!straight_timing_start_ && s >= straight_start_s_) straight_timing_start_ = now;
      const double finish_s = straight_start_s_ + config_.mission.acceleration_length;
      if (mission_ == Mission::Acceleration && !finished_ && s >= finish_s) {
        const double t = now - straight_timing_start_.value_or(mission_start_);
        lap_times_.push_back(t);
        out.lap = LapEvent{1, now, t};
        finish(now);
      }
      break;
    }
    case Mission::Skidpad: {
      if (!skidpad_plan_ || !last_follow || !last_follow->ok) break;
      const double s = last_follow->s;
      while (skidpad_mark_ < 5 && s >= skidpad_plan_->crossing_s[static_cast<std::size_t>(skidpad_mark_)]) {
        if (skidpad_mark_ > 0 && skidpad_mark_time_) {
          const double t = now - *skidpad_mark_time_;
          lap_times_.push_back(t);
          out.lap = LapEvent{skidpad_mark_, now, t};
        }
        skidpad_mark_time_ = now;
        ++skidpad_mark_;
      }
      if (skidpad_mark_ >= 5) finish(now);
      break;
    }
    case Mission::Inspection:
      if (now - mission_start_ >= config_.mission.inspection_duration) finish(now);
      break;
    case Mission::None:
      break;
  }
}

void Autopilot::build_lap(Stamp now, Stamp t1, std::vector<Vec2> ahead, ControlOutput& out) {
  const Stamp t0 = lap1_start_.value_or(mission_start_);
  if (!lap_builder_) {
    use_lap_build(now, trajectory_.build(t0, t1, cones_, convention_, SpeedProfile(lap2_limits()), ahead), out);
    return;
  }
  // The job gets copies: lap 1's poses keep being recorded and the map keeps growing meanwhile.
  LapBuildJob job = [trajectory = trajectory_, t0, t1, cones = cones_, convention = convention_,
                     profile = SpeedProfile(lap2_limits()),
                     ahead = std::move(ahead)] { return trajectory.build(t0, t1, cones, convention, profile, ahead); };
  if (lap_builder_->submit(job)) {
    build_pending_ = true;
    return;
  }
  use_lap_build(now, job(), out);  // no worker to be had: build it here
}

void Autopilot::take_lap_build(Stamp now, ControlOutput& out) {
  if (!build_pending_) return;
  std::optional<TrajectoryResult> built = lap_builder_->poll();
  if (!built) return;
  build_pending_ = false;
  use_lap_build(now, *built, out);
}

void Autopilot::use_lap_build(Stamp now, const TrajectoryResult& built, ControlOutput& out) {
  if (built.path) {
    pending_early_ = false;
    lap_path_ = *built.path;
    lap_zones_ = built.zones;
    lap2_follower_.reset();
    out.lap_line = summary(built);
    return;
  }
  if (pending_early_) {
    // The early build failed: it is tried again while the car is short of the line, or, past the line, the lap is
    // built to the line.
    pending_early_ = false;
    if (lap1_end_) build_lap(now, *lap1_end_, {}, out);
    return;
  }
  supervisor_.report(now, "mission", "lap-2 trajectory not built: " + built.reason, "keep real-time planning");
}

SpeedLimits Autopilot::lap2_limits() const {
  SpeedLimits l = config_.speed.known();
  l.mu = config_.speed.mu * config_.lap2.mu_margin;
  return l;
}

const Path* Autopilot::select_path(Stamp now, PathSource& source) {
  switch (mission_) {
    case Mission::Trackdrive:
    case Mission::Autocross: {
      if (run_out_) {
        source = PathSource::Straight;
        return &*run_out_;
      }
      const bool lap2 = lap_path_ && lap_counter_ && target_laps() > 1;  // from shortly before the first line
      const bool gnss_ok = gnss_good_ && gnss_good_since_ && now - *gnss_good_since_ <= config_.gnss_timeout;
      if (lap2) {
        supervisor_.report(now, "gnss", "fix lost", "fallback to real-time planning", !gnss_ok);
        if (gnss_ok) {
          source = PathSource::Recorded;
          return &*lap_path_;
        }
      }
      source = plan_ ? PathSource::Planner : PathSource::None;
      return plan_ ? &*plan_ : nullptr;
    }
    case Mission::Acceleration:
    case Mission::EbsTest:
      source = straight_ ? PathSource::Straight : PathSource::None;
      return straight_ ? &*straight_ : nullptr;
    case Mission::Skidpad:
      if (skidpad_plan_) {
        source = PathSource::Skidpad;
        return &skidpad_plan_->path;
      }
      source = entry_ ? PathSource::Straight : PathSource::None;
      return entry_ ? &*entry_ : nullptr;
    default:
      source = PathSource::None;
      return nullptr;
  }
}

ControlOutput Autopilot::step(Stamp now) {
  ControlOutput out;
  out.command.stamp = now;
  out.planned = plan_outcome_.planned;
  out.plan_ok = plan_outcome_.ok;
  out.plan_one_boundary = plan_outcome_.one_boundary;
  out.plan_colour_blind = plan_outcome_.colour_blind;
  out.plan_tight_turn = plan_outcome_.tight_turn;
  plan_outcome_ = {};
  const double speed = state_ ? std::max(0.0, state_->speed()) : 0.0;
  if (state_) {
    const Vec2 p = state_->pose.position();
    if (last_position_) odometer_ += (p - *last_position_).norm();
    last_position_ = p;
  }
  const bool driving = supervisor_.as_state() == AsState::Driving;
  if (driving && !started_ && state_) start_mission(now);

  // Paths of the mission: real-time plan (plan()), acceleration straight, skid pad figure of eight.
  if (uses_planner() && started_ && out.plan_ok) detect_open_end(now);
  // The lane is refitted as more of it is seen, until the car is well down it: at speed a refit's sideways jump
  // would only shake the car.
  const bool lane_settled = straight_ && straight_timing_start_ && progress_s_ > straight_start_s_ + 30.0;
  if (state_ && (mission_ == Mission::Acceleration || mission_ == Mission::EbsTest) && new_cones_ && !finished_ &&
      !lane_settled) {
    new_cones_ = false;
    const Pose2 origin = started_ ? start_pose_ : state_->pose;
    const double length = 2.0 * config_.mission.acceleration_length + config_.mission.acceleration_stop_distance;
    if (auto line = straight_from_cones(cones_, origin, length, config_.planner.ds)) {
      SpeedConfig sc = config_.speed;
      SpeedProfile(sc.known()).apply(*line, 0, sc.v_max);
      line->stamp = cones_stamp_;
      const auto timing = timing_line_from_cones(cones_, origin, convention_);
      const auto foot = timing ? project(*line, timing->mid()) : std::nullopt;
      straight_start_s_ = foot ? foot->s : config_.mission.acceleration_start_offset;
      straight_ = std::move(*line);
    }
  }
  if (state_ && mission_ == Mission::Skidpad && new_cones_) {
    new_cones_ = false;
    const Pose2 origin = started_ ? start_pose_ : state_->pose;
    if (!entry_) {
      Path e;
      for (int i = 0; i <= 120; ++i)
        e.points.push_back({origin.transform(Vec2(0.25 * i, 0.0)), 0, 0, 0, config_.mission.skidpad_entry_speed});
      compute_geometry(e);
      entry_ = std::move(e);
    }
    // Refit while still on the entry lane: more of the circles are seen as the car approaches.
    if (skidpad_mark_ == 0) {
      const bool on_entry = !skidpad_plan_ || progress_s_ < skidpad_plan_->crossing_s[0] - 3.0;
      if (on_entry) {
        if (auto g = fit_skidpad(cones_, origin, convention_)) {
          SkidpadPlan plan = skidpad_path(*g, origin, config_.mission.skidpad_exit_length, config_.planner.ds);
          SpeedLimits limits = config_.speed.known();
          limits.mu = config_.speed.mu * config_.speed.mu_margin_skidpad;
          SpeedProfile(limits).apply(plan.path, speed, 0.0);
          plan.path.stamp = cones_stamp_;
          skidpad_ = g;
          skidpad_plan_ = std::move(plan);
          follower_.reset();
        }
      }
    }
  }
  // The fixed paths count as plans for the watchdog while they exist.
  if ((straight_ && (mission_ == Mission::Acceleration || mission_ == Mission::EbsTest)) ||
      (mission_ == Mission::Skidpad && (skidpad_plan_ || entry_)) || run_out_)
    supervisor_.heartbeat(InputStream::Plan, now);

  // Follow the mission's path.
  PathSource source = PathSource::None;
  const Path* path = state_ ? select_path(now, source) : nullptr;
  FollowResult follow;
  if (path && state_) {
    PathFollower& f = source == PathSource::Recorded ? lap2_follower_ : follower_;
    // Back on a path after another one (GNSS regained): the follower's projection hint is from long ago.
    if (source != last_source_) f.reset();
    follow = f.follow(*path, *state_, now, config_.speed.v_max);
    if (follow.ok) progress_s_ = follow.s;
  }
  if (driving && started_ && state_) update_mission(now, path ? &follow : nullptr, out);

  // Mission speed limits on top of the path's own profile.
  double cap = config_.speed.v_max;
  const bool straight_mission = mission_ == Mission::Acceleration || mission_ == Mission::EbsTest;
  if (finished_)
    cap = std::min(cap,
                   stop_speed(finish_speed_, odometer_ - finish_odometer_,
                              straight_mission ? config_.mission.acceleration_stop_decel : config_.mission.stop_decel,
                              stop_distance_));
  // Never faster than the car can stop before a cone across its straight (a short braking zone's closing row):
  // braking zones differ from event to event and the row is only seen from 20 m or so.
  if (straight_mission && started_) {
    if (const auto d = cone_across_straight()) {
      const double room = *d - config_.mission.lane_end_margin;
      cap = std::min(cap, room > 0 ? std::sqrt(2.0 * 0.8 * config_.speed.a_brake_max * room) : 0.0);
    }
  }
  ControlCommand cmd = follow.command;
  cmd.stamp = now;
  cmd.target_speed = std::min(cmd.target_speed, cap);
  if (mission_ == Mission::Inspection) {
    const double t = now - mission_start_;
    const double amplitude = config_.mission.inspection_amplitude * config_.follower.max_steer;
    cmd.steering = started_ ? amplitude * std::sin(2 * std::numbers::pi * t / config_.mission.inspection_period) : 0;
    cmd.target_speed = finished_ ? 0.0 : config_.mission.inspection_speed;
  }

  // Supervision: no motion outside Driving, controlled stop on faults, Ready/Finished/Emergency requests.
  const Supervision sup = supervisor_.evaluate(now, speed, finished_);
  out.request = sup.request;
  if (mission_ == Mission::EbsTest && driving && straight_ && state_) {
    const auto proj = project(*straight_, state_->pose.position());
    if (proj && proj->s >= straight_start_s_ + config_.mission.ebs_trigger_distance) {
      out.request = AsRequest::Emergency;
      finish(now);
    }
  }
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
  out.finished = finished_;
  out.stopping = supervisor_.stopping();
  return out;
}

}  // namespace fsd
