#include "control/missions/mission_skidpad.hpp"

#include <algorithm>
#include <cmath>

#include "control/planning/footprint.hpp"

namespace fsd {

SkidpadMission::SkidpadMission(const AutopilotConfig& config, ColourConvention convention)
    : MissionRun(config), convention_(std::move(convention)) {}

MissionPath SkidpadMission::update_path(const MissionInput& in) {
  MissionPath out;
  const bool fresh = in.state && in.cones && in.cones_seq != cones_seen_;
  if (fresh) {
    cones_seen_ = in.cones_seq;
    const Pose2 origin = started() ? start_pose_ : in.state->pose;
    if (!entry_) {
      Path e;
      for (int i = 0; i <= 120; ++i)
        e.points.push_back({origin.transform(Vec2(0.25 * i, 0.0)), 0, 0, 0, config_.mission.skidpad_entry_speed});
      compute_geometry(e);
      entry_ = std::move(e);
    }
    // Refit on each fresh map until the car drives the left circle: more of the circles are seen as the car
    // approaches and drives the right one, and a figure fitted from the entry alone can miss the far circle by a
    // metre. Not near a crossing, where the laps are counted.
    constexpr double kCrossingClear = 3.0;  // m
    bool refit = !plan_;
    if (plan_ && crossings_ < 3) {
      refit = true;
      for (const double c : plan_->crossing_s) refit = refit && std::abs(in.progress_s - c) > kCrossingClear;
    }
    if (refit) {
      if (auto g = fit_skidpad(*in.cones, origin, convention_)) {
        SkidpadPlan plan = skidpad_path(*g, origin, config_.mission.skidpad_exit_length, config_.planner.ds);
        plan_speed_ = std::max(0.0, in.state->speed());
        SpeedProfile(limits()).apply(plan.path, plan_speed_, 0.0);
        plan.path.stamp = in.cones_stamp;
        // The car's place on the new figure is looked for where it was on the old one: on the entry before the
        // first crossing, else within a few metres (the figure passes its crossing five times).
        const Vec2 p = in.state->pose.position();
        const auto at = crossings_ == 0 ? project(plan.path, p, 0.0, 0.0, plan.crossing_s[0])
                                        : project(plan.path, p, in.progress_s, kCrossingClear, kCrossingClear);
        if (at) out.resume_s = at->s;
        geometry_ = g;
        plan_ = std::move(plan);
        out.replaced = true;
      }
    }
  }
  if (plan_ && fresh) cut_to_free(in);
  out.fixed = plan_ || entry_;
  if (!in.state) return out;
  if (plan_) {
    out.source = PathSource::Skidpad;
    out.path = drive_ ? &*drive_ : &plan_->path;
  } else if (entry_) {
    out.source = PathSource::Straight;
    out.path = &*entry_;
  }
  return out;
}

SpeedLimits SkidpadMission::limits() const {
  SpeedLimits l = config_.speed.known();
  l.mu = config_.speed.mu * config_.speed.mu_margin_skidpad;
  return l;
}

void SkidpadMission::cut_to_free(const MissionInput& in) {
  const Path& path = plan_->path;
  const std::vector<Obstacle> obstacles =
      obstacles_of(*in.cones, config_.path.cone_radius, config_.path.big_cone_radius);
  const SweepResult sweep = sweep_body(path, obstacles, config_.path.body, config_.path.accept_clearance, 0.1,
                                       std::max(0.0, in.progress_s), path.length());
  if (!std::isfinite(sweep.first_short_s)) {
    drive_.reset();
    return;
  }
  // The figure of eight's points stay (the follower keeps its place on it); its speeds stop before the cone.
  drive_ = path;
  SpeedProfile(limits()).apply_until(*drive_, plan_speed_, sweep.first_short_s);
}

MissionEvents SkidpadMission::progress(const MissionInput& in, const FollowResult* follow) {
  MissionEvents out;
  if (!plan_ || !follow || !follow->ok) return out;
  // Crossing 0 starts the first circle's clock, each later one ends a circle, the fifth the mission.
  while (crossings_ < 5 && follow->s >= plan_->crossing_s[static_cast<std::size_t>(crossings_)]) {
    if (crossings_ > 0 && last_crossing_) out.laps.push_back(LapEvent{crossings_, in.now, in.now - *last_crossing_});
    last_crossing_ = in.now;
    ++crossings_;
  }
  if (crossings_ >= 5) finish(in, config_.mission.stop_distance);
  return out;
}

}  // namespace fsd
