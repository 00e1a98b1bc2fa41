#include "control/tracking/follower.hpp"

#include <algorithm>
#include <cmath>

#include "common/car.hpp"

namespace fsd {

namespace {
constexpr double kMaxStateAge = 0.1;  // s: an older state is the supervisor's (a stale pose), not a prediction's
}  // namespace

std::optional<FollowerType> follower_type_from_string(const std::string& s) {
  if (s == "pure_pursuit") return FollowerType::PurePursuit;
  if (s == "stanley") return FollowerType::Stanley;
  if (s == "lqr") return FollowerType::Lqr;
  return std::nullopt;
}

std::string to_string(FollowerType t) {
  switch (t) {
    case FollowerType::PurePursuit:
      return "pure_pursuit";
    case FollowerType::Stanley:
      return "stanley";
    case FollowerType::Lqr:
      return "lqr";
  }
  return "pure_pursuit";
}

Pose2 predict_bicycle(const Pose2& pose, double v, double delta, double wheelbase, double dt) {
  // Exact integration of the kinematic bicycle at constant v and delta (an arc, or a line).
  const double w = v * kinematic_curvature(delta, wheelbase);
  Pose2 out = pose;
  if (std::abs(w * dt) < 1e-9) {
    out.x += v * dt * std::cos(pose.yaw);
    out.y += v * dt * std::sin(pose.yaw);
  } else {
    const double r = v / w;
    out.x += r * (std::sin(pose.yaw + w * dt) - std::sin(pose.yaw));
    out.y -= r * (std::cos(pose.yaw + w * dt) - std::cos(pose.yaw));
    out.yaw = wrap_angle(pose.yaw + w * dt);
  }
  return out;
}

PathFollower::PathFollower(FollowerConfig config) { set_config(config); }

void PathFollower::set_config(const FollowerConfig& c) {
  if (const auto t = follower_type_from_string(c.type)) type_ = *t;
  config_ = c;
  config_.type = to_string(type_);
}

FollowResult PathFollower::follow(const Path& path, const VehicleState& state, Stamp now, double speed_cap) {
  FollowResult r;
  r.command.stamp = now;
  r.command.steering = 0;
  r.command.target_speed = 0;
  const double v = std::max(0.0, state.speed());
  const Pose2& pose0 = state.pose;
  if (path.empty() || !std::isfinite(pose0.x) || !std::isfinite(pose0.y) || !std::isfinite(pose0.yaw) ||
      !std::isfinite(v)) {
    hint_.reset();
    return r;
  }
  // Where the car will be when this command acts: the state is as old as its stamp (a fused estimate stands at
  // its newest measurement, 10-20 ms back), and the actuation latency comes on top. At 1.5 rad/s, 10 ms of age
  // taken as none is a degree of heading error the law steers against.
  const double delta_now = std::isfinite(state.steering) ? state.steering : 0.0;
  const double age = std::isfinite(state.stamp) ? std::clamp(now - state.stamp, 0.0, kMaxStateAge) : 0.0;
  const Pose2 pose = predict_bicycle(pose0, v, delta_now, config_.wheelbase, std::max(0.0, config_.latency) + age);

  const bool same_path =
      hint_ && hint_->stamp == path.stamp && hint_->size == path.points.size() && hint_->length == path.length();
  const auto proj = same_path ? project(path, pose.position(), hint_->s, config_.search_window, config_.search_window)
                    : near_s_ ? project(path, pose.position(), *near_s_, config_.search_window, config_.search_window)
                              : project(path, pose.position());
  near_s_.reset();
  if (!proj) return r;
  hint_ = Hint{path.stamp, path.points.size(), path.length(), proj->s};
  r.s = proj->s;
  r.cross_track = proj->lateral;
  r.heading_error = wrap_angle(pose.yaw - proj->yaw);
  r.target = proj->foot;
  if (proj->distance() > config_.max_offset) return r;  // off path: straight wheels, stop

  double delta = 0;
  switch (type_) {
    case FollowerType::PurePursuit:
      delta = pure_pursuit(path, pose, v, proj->s, r.target);
      break;
    case FollowerType::Stanley:
      delta = stanley(path, pose, v, proj->s);
      break;
    case FollowerType::Lqr:
      delta = lqr(path, *proj, pose, v);
      break;
  }
  if (!std::isfinite(delta)) delta = 0;
  r.command.steering = std::clamp(delta, -config_.max_steer, config_.max_steer);
  // The speed a little ahead: the speed loop lags, and at standstill on a profile starting from zero the
  // car must still be asked to move off.
  const double preview = std::max(v * std::max(0.0, config_.speed_preview), 1.0);
  const PathPoint ahead = sample(path, proj->s + preview);
  // Acceleration feed-forward: a proportional speed loop only accelerates (or brakes) on an error, so the target
  // leads the profile by its acceleration a = d(v²)/2ds times the loop's time constant.
  double target = ahead.v;
  if (config_.speed_lead > 0 || config_.speed_lead_brake > 0) {
    constexpr double kDs = 1.0;  // m over which the profile's acceleration is taken
    const double v2 = sample(path, proj->s + preview + kDs).v;
    const double a = (v2 * v2 - ahead.v * ahead.v) / (2 * kDs);
    target += (a > 0 ? config_.speed_lead : config_.speed_lead_brake) * a;
  }
  if (config_.governor_gain > 0) {
    const double excess = proj->distance() - config_.governor_offset;
    const bool saturated = std::abs(delta) >= config_.max_steer;
    // Never below a crawl: a car standing off the line must still be able to drive back onto it.
    const double cap = std::max(v - config_.governor_gain * std::max(0.0, excess), config_.governor_floor);
    if (excess > 0 || saturated) target = std::min(target, cap);
  }
  r.command.target_speed = std::clamp(target, 0.0, std::max(0.0, speed_cap));
  r.ok = true;
  return r;
}

}  // namespace fsd
