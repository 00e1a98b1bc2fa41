#include "control/supervisor/as_supervisor.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace fsd {

std::string_view to_string(InputStream s) {
  switch (s) {
    case InputStream::Lidar:
      return "lidar";
    case InputStream::Pose:
      return "pose";
    case InputStream::Gnss:
      return "gnss";
    case InputStream::Vcu:
      return "vcu";
    case InputStream::Plan:
      return "planning";
    case InputStream::Camera:
      return "camera";
  }
  return "?";
}

namespace {
std::size_t idx(InputStream s) { return static_cast<std::size_t>(s); }
std::string with_unit(double v, const char* unit) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f %s", v, unit);
  return buf;
}
std::string seconds(double s) { return with_unit(s, "s"); }
}  // namespace

AsSupervisor::AsSupervisor(SupervisorConfig config) : config_(config) {}

void AsSupervisor::require(InputStream s, bool required) {
  if (s == InputStream::Pose || s == InputStream::Vcu) return;  // always needed
  required_[idx(s)] = required;
}

namespace {
// Why the VCU is in AS Emergency, from its Status fault bits (docs/vcu-protocol.md).
std::string emergency_cause(std::uint32_t faults) {
  namespace vcu = wire::vcu;
  if (faults & vcu::kFaultEmergencyHeartbeat) return "the stack's heartbeat was lost (the stack stopped or stalled)";
  if (faults & vcu::kFaultEmergencyRes) return "the RES emergency stop";
  if (faults & vcu::kFaultEmergencyRequest) return "the stack's own request";
  if (faults & vcu::kFaultEmergencyAsms) return "the ASMS switched off while driving";
  return "a cause the VCU did not name";
}
}  // namespace

void AsSupervisor::on_vcu(const VcuStatus& status) {
  // AS Emergency is the VCU's (EBS engaged, only the ASMS switched off leaves it): logged with its cause when it
  // begins, also when it was already so before this stack started (restarted after a crash), unless this stack
  // asked for it (its own fault is logged), and cleared when it ends.
  const bool was = status_ && status_->as_state == AsState::Emergency;
  const bool is = status.as_state == AsState::Emergency;
  const bool asked = emergency_asked_ && (status.faults & wire::vcu::kFaultEmergencyRequest);
  if (is && !was && !asked) {
    emergency_what_ = "AS Emergency: " + emergency_cause(status.faults);
    raise(status.stamp, "vcu", emergency_what_, "EBS engaged: nothing is driven until the ASMS is switched off (AS Off)");
  } else if (was && !is) {
    clear(status.stamp, "vcu", emergency_what_);
  }
  status_ = status;
  heartbeat(InputStream::Vcu, status.stamp);
}

void AsSupervisor::heartbeat(InputStream s, Stamp t) {
  if (!std::isfinite(t)) return;
  auto& last = last_[idx(s)];
  if (!last || t > *last) last = t;
}

void AsSupervisor::on_plan(Stamp t, bool ok, const std::string& why) {
  if (ok) heartbeat(InputStream::Plan, t);
  plan_why_ = why;
}

void AsSupervisor::report(Stamp t, const std::string& source, const std::string& what, const std::string& action,
                          bool active) {
  if (active)
    raise(t, source, what, action);
  else
    clear(t, source, what);
}

bool AsSupervisor::stale(InputStream s, Stamp now, double timeout) const {
  const auto& last = last_[idx(s)];
  if (!last) return true;
  return now - *last > timeout;
}

void AsSupervisor::raise(Stamp t, const std::string& source, const std::string& what, const std::string& action) {
  const auto key = std::make_pair(source, what);
  if (std::find(active_.begin(), active_.end(), key) != active_.end()) return;
  active_.push_back(key);
  if (static_cast<int>(faults_.size()) < config_.max_faults) faults_.push_back({t, source, what, action, std::nullopt});
}

void AsSupervisor::clear(Stamp t, const std::string& source, const std::string& what) {
  const auto key = std::make_pair(source, what);
  const auto it = std::find(active_.begin(), active_.end(), key);
  if (it == active_.end()) return;
  active_.erase(it);
  for (auto f = faults_.rbegin(); f != faults_.rend(); ++f)
    if (f->source == source && f->what == what) {
      if (!f->cleared) f->cleared = t;
      break;
    }
}

void AsSupervisor::stop(Stamp t, const std::string& source, const std::string& what) {
  raise(t, source, what, "controlled stop");
  if (!stop_reason_) {
    stop_reason_ = source + ": " + what;
    stop_since_ = t;
  }
}

Supervision AsSupervisor::evaluate(Stamp now, double speed, bool finished) {
  Supervision out;
  const AsState state = as_state();
  const bool vcu_stale = stale(InputStream::Vcu, now, config_.vcu_timeout);
  // Standstill bookkeeping (for Ready, Finished and Emergency requests).
  if (std::abs(speed) < config_.standstill_speed) {
    if (!standing_since_) standing_since_ = now;
  } else {
    standing_since_.reset();
  }
  const bool standing = standing_since_ && now - *standing_since_ >= config_.standstill_time;
  // A camera that stopped sending changes no decision (the LiDAR stages carry on alone): watched in every state,
  // once it has sent a frame, so the log says when it went and came back.
  const std::string camera_lost = "no frames for " + seconds(config_.camera_timeout);
  if (last_[idx(InputStream::Camera)] && stale(InputStream::Camera, now, config_.camera_timeout))
    raise(now, "camera", camera_lost, "LiDAR-only detections, colour from reflectivity");
  else
    clear(now, "camera", camera_lost);

  if (state != AsState::Driving) {
    driving_since_.reset();
    // Ask for Ready when a mission is chosen and every stream it needs is alive, at standstill.
    if (state == AsState::Off && mission_ != Mission::None && !vcu_stale && standing && !stop_reason_) {
      bool healthy = !stale(InputStream::Pose, now, config_.pose_timeout);
      if (required_[idx(InputStream::Lidar)])
        healthy = healthy && !stale(InputStream::Lidar, now, config_.lidar_timeout);
      if (healthy) out.request = AsRequest::Ready;
    }
    return out;  // no motion outside Driving
  }
  if (!driving_since_) driving_since_ = now;

  // Watchdogs. Streams count from the start of Driving: before it they may legitimately be idle.
  if (vcu_stale) stop(now, "vcu", "status stale (> " + seconds(config_.vcu_timeout) + ")");
  if (stale(InputStream::Pose, now, config_.pose_timeout))
    stop(now, "pose", "pose stale (> " + seconds(config_.pose_timeout) + ")");
  double cap = 1e9;
  if (required_[idx(InputStream::Lidar)] && stale(InputStream::Lidar, now, config_.lidar_timeout)) {
    if (stale(InputStream::Lidar, now, config_.lidar_stop_timeout))
      stop(now, "lidar", "no cone detections for " + seconds(config_.lidar_stop_timeout));
    raise(now, "lidar", "detections stale", "slow down to " + with_unit(config_.degraded_speed, "m/s"));
    cap = config_.degraded_speed;
  } else {
    clear(now, "lidar", "detections stale");
  }
  if (required_[idx(InputStream::Plan)] && !finished) {
    const auto& last = last_[idx(InputStream::Plan)];
    const Stamp since = last ? std::max(*last, *driving_since_) : *driving_since_;
    if (now - since > config_.plan_timeout)
      stop(now, "planning", "no usable plan for " + seconds(config_.plan_timeout) + plan_why());
  }
  // A car standing in Driving before its finish has no way on (a lane closed by cones it will not drive into, a
  // path it cannot follow): end the mission with that reason rather than stand there until someone presses RES.
  if (required_[idx(InputStream::Plan)] && !finished && standing_since_ &&
      now - std::max(*standing_since_, *driving_since_) > config_.stuck_timeout)
    stop(now, "mission", "standing for " + seconds(config_.stuck_timeout) + " before the finish" + plan_why());

  if (stop_reason_) {
    out.controlled_stop = true;
    out.speed_cap = 0;
    if (standing && config_.emergency_after_fault_stop) out.request = AsRequest::Emergency;
    if (!standing && now - stop_since_ > config_.stop_timeout) {
      raise(now, "supervisor", "controlled stop too slow", "emergency");
      out.request = AsRequest::Emergency;
    }
    return out;
  }
  out.may_move = true;
  out.speed_cap = cap;
  if (finished && standing) out.request = AsRequest::Finished;
  return out;
}

}  // namespace fsd
