#include "control/missions/mission_trackdrive.hpp"

#include <algorithm>
#include <cmath>

namespace fsd {

namespace {
LapLineBuilt summary(const TrajectoryResult& r) {
  return {r.path ? r.path->length() : 0.0, r.closure_gap, r.recentre_rms, r.clearance};
}
}  // namespace

TrackdriveMission::TrackdriveMission(const AutopilotConfig& config, Mission mission, ColourConvention convention)
    : MissionRun(config), mission_(mission), convention_(std::move(convention)), trajectory_(config.trajectory) {}

int TrackdriveMission::target_laps() const { return mission_ == Mission::Autocross ? 1 : config_.mission.laps; }

void TrackdriveMission::set_config(const AutopilotConfig& config) {
  MissionRun::set_config(config);
  if (lap_path_) SpeedProfile(lap2_limits()).apply(*lap_path_, 0, 0);
}

void TrackdriveMission::start(const MissionInput& in) {
  MissionRun::start(in);
  const auto line = in.cones ? timing_line_from_cones(*in.cones, start_pose_, convention_) : std::nullopt;
  lap_counter_.emplace(line ? *line : line_across(start_pose_), config_.laps);
  // A layout whose start pose is past the line (and close to it) times the first lap from the start.
  const double past = lap_counter_->line().past(start_pose_.position());
  if (past > 0 && past < config_.laps.hysteresis) {
    lap_counter_->start_timing_at(in.now);
    lap1_start_ = in.now;
  }
}

bool TrackdriveMission::watching_for_the_end(const MissionInput& in) const {
  // Only the first time round on real-time plans: a loop's recorded lap never ends.
  if (run_out_ || finished() || !in.plan || !in.state || !in.cones || in.plan->points.size() < 2 || !lap_counter_ ||
      lap_counter_->laps_completed() > 0 || config_.mission.open_end_sight <= 0 ||
      in.odometer < config_.mission.open_end_min_travel)
    return false;
  // Only on a fresh view: with the sensors silent, no cones beyond the plan proves nothing; nor just after a gap,
  // while the map has not yet confirmed the cones that came into range meanwhile.
  return in.now - in.cones_stamp <= 0.3 && in.now - in.cones_unbroken_since >= config_.mission.open_end_settle;
}

bool TrackdriveMission::stayed_in_sight(bool in_sight, std::optional<double>& since, double odometer) const {
  if (!in_sight) {
    since.reset();
    return false;
  }
  if (!since) since = odometer;
  return odometer - *since >= config_.mission.open_end_confirm;
}

bool TrackdriveMission::open_end_in_sight(const MissionInput& in) const {
  if (!watching_for_the_end(in)) return false;
  const Path* plan = in.plan;
  const PathPoint& end = plan->points.back();
  const Vec2 dir(std::cos(end.yaw), std::sin(end.yaw));
  // The walk stopped well inside what the sensors see: if the track went on, its next cones (≤ 5 m apart by the
  // rules) would be mapped beyond the last crossing.
  if ((end.p - in.state->pose.position()).norm() > config_.mission.open_end_sight) return false;
  const TimingLine& line = lap_counter_->line();
  if ((end.p - line.mid()).norm() < config_.laps.hysteresis && dir.dot(line.forward) > 0.5)
    return false;  // loop closing
  for (const auto& c : *in.cones) {
    // Timing cones mark a line across the track, not its continuation: an open course's finish line stands at its
    // last cones, a little beyond where the walk between them stops.
    if (!c.position.allFinite() || convention_.role_of(c.colour) == ConeRole::Timing) continue;
    const Vec2 d = c.position.head<2>() - end.p;
    if (d.dot(dir) > 1.0 && d.norm() < 10.0) return false;
  }
  return true;
}

bool TrackdriveMission::detect_open_end(const MissionInput& in) {
  // Believed once the end stayed in sight on every fresh plan over open_end_confirm driven: a plan that ends short
  // for a moment (a sharp turn beyond the walk's end whose cones the real perception has not confirmed yet) is no
  // end of the track; it ended epfl_autoX_Vaudoise_Sponso's first lap in its slalom.
  if (!stayed_in_sight(open_end_in_sight(in), open_end_since_, in.odometer)) return false;
  const PathPoint& end = in.plan->points.back();
  run_out(in, *in.plan, Vec2(std::cos(end.yaw), std::sin(end.yaw)));
  return true;
}

void TrackdriveMission::run_out(const MissionInput& in, Path out, const Vec2& dir) {
  out.closed = false;
  compute_geometry(out);  // the arc lengths of a path cut at its end line
  open_end_s_ = out.length();
  const Vec2 end = out.points.back().p;
  const double ds = std::max(0.05, config_.planner.ds);
  for (double s = ds; s <= config_.mission.stop_distance + 1e-9; s += ds)
    out.points.push_back({end + s * dir, 0, 0, 0, 0});
  compute_geometry(out);
  SpeedProfile(config_.speed.realtime()).apply(out, std::max(0.0, in.state->speed()), 0.0);
  run_out_ = std::move(out);
}

std::optional<TimingLine> TrackdriveMission::finish_line_in_sight(const MissionInput& in) const {
  if (!watching_for_the_end(in)) return std::nullopt;
  // Timing cones on both sides ahead: one misnamed cone is no line.
  auto line =
      timing_line_from_cones(*in.cones, in.state->pose, convention_, 0, 0.0, config_.mission.open_end_sight, true);
  // The start line is the loop's; a line away from it ends an open course.
  if (!line || (line->mid() - lap_counter_->line().mid()).norm() < config_.laps.hysteresis) return std::nullopt;
  return line;
}

bool TrackdriveMission::detect_finish_line(const MissionInput& in) {
  // Believed once it stayed in sight on every fresh plan over open_end_confirm driven, as the open end.
  const auto line = finish_line_in_sight(in);
  if (!stayed_in_sight(line.has_value(), finish_since_, in.odometer)) return false;
  // The plan up to the line, where the run ends; a plan that does not reach it is no run-out yet.
  Path to_line = *in.plan;
  const auto& pts = to_line.points;
  const auto past = std::find_if(pts.begin(), pts.end(), [&](const PathPoint& q) { return line->past(q.p) >= 0; });
  if (past == pts.begin() || past == pts.end()) return false;
  const PathPoint& a = *(past - 1);
  const double da = line->past(a.p), db = line->past(past->p);
  PathPoint at = a;
  at.p = a.p + (past->p - a.p) * (da / (da - db));
  to_line.points.erase(past, to_line.points.end());
  to_line.points.push_back(at);
  run_out(in, std::move(to_line), line->forward);
  return true;
}

MissionPath TrackdriveMission::update_path(const MissionInput& in) {
  MissionPath out;
  if (started() && in.plan_ok) out.replaced = detect_finish_line(in) || detect_open_end(in);
  out.fixed = run_out_.has_value();
  if (!in.state) return out;
  if (run_out_) {
    out.source = PathSource::Straight;
    out.path = &*run_out_;
    return out;
  }
  // The recorded lap from shortly before the first line, while the pose is anchored: a good GNSS fix, or without
  // one the pose matched to the cone map lap 1 built (the LiDAR odometry carries it between matches).
  if (lap_path_ && lap_counter_ && target_laps() > 1) {
    // Without satellites (no good fix ever) the cone map alone anchors the pose: its loss is the fault.
    const bool anchored = in.gnss_ok || in.map_matched;
    out.faults.push_back({"gnss", "fix lost", "fallback to real-time planning", in.gnss_seen && !anchored});
    out.faults.push_back({"gnss", "fix lost, the pose held to the cone map", "recorded lap kept",
                          in.gnss_seen && !in.gnss_ok && anchored});
    out.faults.push_back({"localization", "pose not matched to the cone map", "fallback to real-time planning",
                          !in.gnss_seen && !anchored});
    if (anchored) {
      out.source = PathSource::Recorded;
      out.path = &*lap_path_;
      return out;
    }
  }
  out.source = in.plan ? PathSource::Planner : PathSource::None;
  out.path = in.plan;
  return out;
}

MissionEvents TrackdriveMission::progress(const MissionInput& in, const FollowResult* follow) {
  MissionEvents out;
  if (!lap_counter_ || !in.state) return out;
  const VehicleState& st = *in.state;
  const Vec2 pos = st.pose.position();
  take_lap_build(in, out);
  // Past lap 1's line when a loop closure dropped the lap path: built again to the line from the moved poses
  // (before the line, the early build or the line's does it).
  if (rebuild_ && !lap_path_ && !build_pending_ && lap1_end_ && target_laps() > 1) {
    rebuild_ = pending_early_ = false;
    build_lap(in, *lap1_end_, {}, out);
  }
  const bool was_timing = lap_counter_->timing();
  const auto ev = lap_counter_->update(in.now, pos);
  if (!was_timing && lap_counter_->timing() && !lap1_start_) lap1_start_ = lap_counter_->last_crossing();
  if (lap_counter_->laps_completed() == 0) trajectory_.record(st);
  // An open layout ends at its last cones: one run, timed from the start of the mission.
  if (run_out_ && !finished() && follow && follow->ok && follow->s >= open_end_s_) {
    out.laps.push_back(LapEvent{1, in.now, in.now - lap1_start_.value_or(start_time_)});
    finish(in, config_.mission.stop_distance);
    return out;
  }
  // Shortly before the end of lap 1, close the lap with the plan ahead and take it: the car then crosses the
  // line at the lap's speed, so lap 2 is a flying lap.
  const double early = config_.trajectory.early_build_distance;
  if (!lap_path_ && !build_pending_ && !ev && early > 0 && target_laps() > 1 && lap_counter_->laps_completed() == 0 &&
      lap_counter_->timing() && in.plan && in.odometer > config_.trajectory.min_lap_length) {
    const TimingLine& line = lap_counter_->line();
    const double before = -line.past(pos);
    const bool across = std::abs((pos - line.mid()).dot(Vec2(-line.forward.y(), line.forward.x()))) <
                        0.5 * (line.b - line.a).norm() + config_.laps.line_margin;
    const Vec2 heading(std::cos(st.pose.yaw), std::sin(st.pose.yaw));
    if (before > 0 && before < early && across && heading.dot(line.forward) > 0.7) {
      std::vector<Vec2> ahead;
      for (const auto& q : in.plan->points) ahead.push_back(q.p);
      pending_early_ = true;
      build_lap(in, in.now, std::move(ahead), out);
    }
  }
  if (ev) {
    out.laps.push_back(*ev);
    if (ev->lap == 1) lap1_end_ = ev->t;
    // No lap path yet: built to the line now, unless the early build is still under way (should that one
    // fail, this one follows).
    if (ev->lap == 1 && target_laps() > 1 && !lap_path_ && !build_pending_) {
      pending_early_ = false;
      build_lap(in, ev->t, {}, out);
    }
    if (ev->lap >= target_laps()) finish(in, config_.mission.stop_distance);
  }
  return out;
}

void TrackdriveMission::relocate(const std::function<Pose2(Stamp)>& correction, Stamp now) {
  constexpr double kRebuild = 0.02;  // m: a lap path from poses moved less than this stands
  const double moved = trajectory_.relocate(correction);
  if (run_out_) transform_path(*run_out_, correction(now));
  if (moved < kRebuild || (!lap_path_ && !build_pending_)) return;
  lap_path_.reset();
  discard_build_ = build_pending_;
  rebuild_ = true;
}

void TrackdriveMission::build_lap(const MissionInput& in, Stamp t1, std::vector<Vec2> ahead, MissionEvents& out) {
  static const std::vector<Cone> no_cones;
  const std::vector<Cone>& cones = in.cones ? *in.cones : no_cones;
  const Stamp t0 = lap1_start_.value_or(start_time_);
  if (!lap_builder_) {
    use_lap_build(in, trajectory_.build(t0, t1, cones, convention_, SpeedProfile(lap2_limits()), ahead), out);
    return;
  }
  // The job gets copies: lap 1's poses keep being recorded and the map keeps growing meanwhile.
  LapBuildJob job = [trajectory = trajectory_, t0, t1, cones, convention = convention_,
                     profile = SpeedProfile(lap2_limits()),
                     ahead = std::move(ahead)] { return trajectory.build(t0, t1, cones, convention, profile, ahead); };
  if (lap_builder_->submit(job)) {
    build_pending_ = true;
    return;
  }
  use_lap_build(in, job(), out);  // no worker to be had: build it here
}

void TrackdriveMission::take_lap_build(const MissionInput& in, MissionEvents& out) {
  if (!build_pending_) return;
  std::optional<TrajectoryResult> built = lap_builder_->poll();
  if (!built) return;
  build_pending_ = false;
  if (discard_build_) {  // built from poses moved since: built again below or before the line
    discard_build_ = pending_early_ = false;
    return;
  }
  use_lap_build(in, *built, out);
}

void TrackdriveMission::use_lap_build(const MissionInput& in, const TrajectoryResult& built, MissionEvents& out) {
  if (built.path) {
    pending_early_ = false;
    lap_path_ = *built.path;
    out.lap_line = summary(built);
    return;
  }
  if (pending_early_) {
    // The early build failed: it is tried again while the car is short of the line, or, past the line, the lap is
    // built to the line.
    pending_early_ = false;
    if (lap1_end_) build_lap(in, *lap1_end_, {}, out);
    return;
  }
  out.faults.push_back({"mission", "lap-2 trajectory not built: " + built.reason, "keep real-time planning"});
}

SpeedLimits TrackdriveMission::lap2_limits() const {
  SpeedLimits l = config_.speed.known();
  l.mu = config_.speed.mu * config_.lap2.mu_margin;
  return l;
}

}  // namespace fsd
