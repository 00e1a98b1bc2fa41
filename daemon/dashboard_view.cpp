#include "daemon/dashboard_view.hpp"

#include <memory>
#include <string>

#include "control/missions.hpp"

namespace fsd {

void DashboardView::on_cycle(Stamp now, AsState as, const ControlOutput& out, std::size_t laps_done,
                             const std::optional<Vec2>& position, std::uint64_t cycle) {
  if (out.lap)
    lap_started_ = out.lap->t;
  else if (!lap_started_ && as == AsState::Driving)
    lap_started_ = now;
  if (as != AsState::Driving || !position || cycle % 10 != 0) return;
  auto& trail = laps_done == 0 ? lap1_trail_ : later_trail_;
  if (trail.size() < kMaxTrailPoints) trail.push_back(*position);
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
  s.as.lap = static_cast<int>(autopilot.lap_times().size());
  s.as.laps_total = timed_laps(mission_, trackdrive_laps_);
  s.as.lap_times = autopilot.lap_times();
  s.as.lap_time = lap_started_ && !out.finished ? now - *lap_started_ : 0.0;
  s.as.control_mode = std::string(to_string(out.source));
  s.as.finished = out.finished;
  if (vcu) {
    s.as.res_go = vcu->res_go;
    s.as.res_emergency = vcu->res_emergency;
    s.as.ebs_active = vcu->ebs_active;
  }
  for (const auto& f : autopilot.faults()) s.faults.push_back({f.t, f.source, f.what, f.action, true});
  return s;
}

}  // namespace fsd
