#include "daemon/telemetry/dashboard_view.hpp"

#include <algorithm>
#include <memory>
#include <string>

#include "control/missions/missions.hpp"

namespace fsd {

void DashboardView::on_cycle(Stamp now, AsState as, const ControlOutput& out, std::size_t laps_done,
                             const std::optional<Vec2>& position, std::uint64_t cycle) {
  if (out.lap) {
    lap_started_ = out.lap->t;
    last_lap_time_ = out.lap->time_s;
  } else if (!lap_started_ && as == AsState::Driving) {
    lap_started_ = now;
  }
  laps_done_ = laps_done;
  finished_ = finished_ || out.finished;
  // The clock stops with the car (Emergency, Finished, Off) and runs again only if it drives again.
  if (as == AsState::Driving)
    clock_stopped_.reset();
  else if (lap_started_ && !clock_stopped_)
    clock_stopped_ = now;
  if (as != AsState::Driving || !position || cycle % 10 != 0) return;
  auto& trail = laps_done == 0 ? lap1_trail_ : later_trail_;
  if (trail.size() < kMaxTrailPoints) trail.push_back(*position);
}

int DashboardView::lap_being_driven(bool finished) const {
  const int done = static_cast<int>(laps_done_);
  const int total = timed_laps(mission_, trackdrive_laps_);
  if (finished) return std::max(done, 1);  // the last lap driven, not one more
  return total > 0 ? std::min(done + 1, total) : done + 1;
}

double DashboardView::lap_clock(Stamp now, bool finished) const {
  if (finished && last_lap_time_) return *last_lap_time_;  // the last lap's time, not a new lap from 0:00
  if (!lap_started_) return 0.0;
  return std::max(0.0, clock_stopped_.value_or(now) - *lap_started_);
}

TelemetrySnapshot DashboardView::snapshot(Stamp now, AsState as, const ControlOutput& out, const Autopilot& autopilot,
                                          const std::optional<VcuStatus>& vcu) const {
  TelemetrySnapshot s;
  s.t = now;
  s.target_speed = out.command.target_speed;
  s.cone_map = std::make_shared<const std::vector<Cone>>(autopilot.cones());
  auto paths = std::make_shared<web::PathSet>();
  paths->lap1_trajectory = lap1_trail_;
  paths->lap2_tracking = later_trail_;
  if (out.path)
    for (const auto& p : out.path->points) paths->planned.push_back(p.p);
  s.paths = std::move(paths);
  s.as.as_state = as;
  s.as.mission = mission_;
  s.as.laps_total = timed_laps(mission_, trackdrive_laps_);
  s.as.laps_completed = static_cast<int>(laps_done_);
  s.as.lap = lap_being_driven(out.finished || finished_);
  s.as.lap_times = autopilot.lap_times();
  s.as.lap_time = lap_clock(now, out.finished || finished_);
  s.as.control_mode = std::string(to_string(out.source));
  s.as.finished = out.finished;
  if (vcu) {
    s.as.res_go = vcu->res_go;
    s.as.res_emergency = vcu->res_emergency;
    s.as.ebs_active = vcu->ebs_active;
  }
  for (const auto& f : autopilot.faults()) s.faults.push_back({f.t, f.source, f.what, f.action, !f.cleared});
  return s;
}

void DashboardView::add_truth_path(TelemetrySnapshot& s) {
  if (!s.truth) return;
  const Vec2 p = s.truth->pose.position();
  if (s.as.as_state == AsState::Driving && p.allFinite() && truth_trail_.size() < kMaxTrailPoints &&
      (truth_trail_.empty() || (p - truth_trail_.back()).norm() >= 0.1)) {
    truth_trail_.push_back(p);
    truth_trail_sent_.reset();
  }
  if (!truth_trail_sent_ && truth_trail_.size() >= 2)
    truth_trail_sent_ = std::make_shared<const std::vector<Vec2>>(truth_trail_);
  s.truth_path = truth_trail_sent_;
}

}  // namespace fsd
