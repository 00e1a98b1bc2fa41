#pragma once
// The driving brain in one object, for the daemon's control thread: takes the newest VCU status, cone map,
// fused vehicle state and GNSS quality, and each cycle returns the command for the VCU and the AS request.
// Inside: real-time planning (control/planning), the path followers and the contact guard (control/tracking), the
// AS supervisor (control/supervisor) and the mission (one MissionRun of
// control/mission_*.hpp: trackdrive and autocross with the lap counter and the lap-2 trajectory, acceleration and
// EBS test, skid pad, inspection). No I/O, no threads: the caller owns time (every call carries the stack's clock)
// and calls from one thread.
//
// One control cycle (on each GNSS-INS sample or at 50–100 Hz):
//   on_vcu(status)          the newest VcuStatus
//   on_cones(t, map)        only when mapping produced a new cone map (map frame, all cones so far; ~10 Hz)
//   on_state(state)         the fused VehicleState (map frame; steering = measured wheel angle)
//   on_gnss(t, good)        the newest GNSS-INS sample's GnssSample::good
//   plan(now)               the real-time planner, when new cones arrived or replan_period passed (a few ms)
//   out = step(now)         send out.command to the VCU every cycle, out.request while it is not None;
//                           out.path / out.follow / out.lap / faults() feed telemetry and the scorecard.
// plan() and step() are separate calls so that the caller can time each (the core reads no clock). Lap 2's path
// (built once, 10–30 ms) is built inside step() unless a LapBuildService is set: the daemon on the car hands it to
// a worker so that the control cycle keeps its period, and takes the lap when it is ready.
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include "common/track.hpp"
#include "common/types.hpp"
#include "control/autopilot_config.hpp"
#include "control/missions/lap_build_service.hpp"
#include "control/missions/mission_run.hpp"
#include "control/missions/skidpad.hpp"
#include "control/planning/plan_service.hpp"
#include "control/planning/realtime_planner.hpp"
#include "control/supervisor/as_supervisor.hpp"
#include "control/tracking/contact_guard.hpp"
#include "control/tracking/follower.hpp"

namespace fsd {

class TrackdriveMission;
class SkidpadMission;

struct ControlOutput {
  ControlCommand command;               // to the VCU, every cycle
  AsRequest request = AsRequest::None;  // to the VCU while not None
  PathSource source = PathSource::None;
  const Path* path = nullptr;            // the path followed this cycle (valid until the next call)
  FollowResult follow;                   // tracking diagnostics (cross-track error, look-ahead point)
  std::optional<LapEvent> lap;           // a lap (or skid pad circle, or acceleration run) completed this cycle
  bool planned = false;                  // the real-time planner ran this cycle (plan())
  bool plan_ok = false;                  // its outcome when it ran
  bool plan_one_boundary = false;        // that plan ran half a width inside the only boundary seen
  bool plan_colour_blind = false;        // that plan ignored cone colours that contradicted the geometry
  bool plan_cut_short = false;           // that plan ends before a place its body would come too near a cone
  std::optional<LapLineBuilt> lap_line;  // the lap path was built this cycle
  GuardResult guard;                     // the contact guard's prediction this cycle
  bool finished = false;                 // past the mission's finish (stopping or stopped)
  bool stopping = false;                 // a fault stop is under way
};

class Autopilot {
 public:
  Autopilot(AutopilotConfig config, Mission mission, ColourConvention convention);

  // Inputs: call whenever new data arrives, before step(). Stamps are sensor times on the stack's clock.
  void on_vcu(const VcuStatus& status);
  void on_cones(Stamp t, std::vector<Cone> map_cones);  // the whole cone map, map frame (or detections)
  void on_state(const VehicleState& state);             // fused pose and motion, map frame
  void on_gnss(Stamp t, bool good);                     // each GNSS-INS sample: usable for lap-2 tracking?
  void on_map_match(Stamp t);                           // the localization's pose was matched to the cone map
  void on_camera(Stamp t);                              // the newest camera frame the perception stages use

  // The real-time planner at time `now`, when it is due (new cones, or replan_period since the last attempt);
  // returns whether a plan was taken this cycle. Call before step() in each cycle of a mission that plans
  // (trackdrive, autocross). With a plan service the plan is handed over and taken in a later cycle.
  bool plan(Stamp now);
  // One control cycle at time `now` (≥ the newest input stamp): runs the mission, follows, supervises. Always
  // returns a command; outside AS Driving it holds the car.
  ControlOutput step(Stamp now);

  // Read-outs for telemetry and the scorecard.
  Mission mission() const { return mission_; }
  const Path* realtime_path() const { return plan_ ? &*plan_ : nullptr; }
  const Path* recorded_path() const;
  const std::vector<Fault>& faults() const { return supervisor_.faults(); }
  const std::vector<double>& lap_times() const { return lap_times_; }
  const std::vector<Cone>& cones() const { return cones_; }
  const std::optional<SkidpadGeometry>& skidpad() const;
  bool open_end_seen() const;  // an open layout's end is in sight
  AsState as_state() const { return supervisor_.as_state(); }
  const AutopilotConfig& config() const { return config_; }

  // A loop closure corrected the localization (map ← estimated, by the instant of the estimate): the state, the
  // plan and what the mission recorded move with it. The caller gives the corrected cone map (on_cones) and state.
  void relocate(const std::function<Pose2(Stamp)>& correction, Stamp now);

  // Live tuning: the planner, follower, speed and supervisor settings take effect from the next step.
  void set_config(const AutopilotConfig& config);
  // Lap 2's path built by `service` (which must outlive the autopilot) instead of inside step(); null: inside step().
  void set_lap_builder(LapBuildService* service);
  // Lap 1's plans made by `service` (which must outlive the autopilot) instead of inside plan(); null: inside.
  void set_plan_service(PlanService* service) { plan_service_ = service; }
  // Fault injection (tests, the virtual car): the planner produces nothing while stalled.
  void set_planner_stalled(bool stalled) { planner_stalled_ = stalled; }

 private:
  // The one place that tells the missions apart: the mission's class, and the typed views of two of them.
  std::unique_ptr<MissionRun> make_run(Mission mission, const ColourConvention& convention);
  MissionInput mission_input(Stamp now, bool plan_ok) const;
  void take_plan(Stamp now, PlanResult r);
  void report(Stamp now, const std::vector<MissionFault>& faults);

  AutopilotConfig config_;
  Mission mission_;
  RealtimePlanner planner_;
  ContactGuard guard_;
  PathFollower follower_;
  PathFollower lap2_follower_;  // on the recorded lap path (its own gains)
  AsSupervisor supervisor_;
  std::unique_ptr<MissionRun> run_;
  TrackdriveMission* trackdrive_ = nullptr;  // run_ of a trackdrive or autocross
  SkidpadMission* skidpad_run_ = nullptr;    // run_ of a skid pad

  // Newest inputs.
  std::optional<VehicleState> state_;
  std::vector<Cone> cones_;
  std::uint64_t cones_seq_ = 0;  // cone maps received
  Stamp cones_stamp_ = -1;
  Stamp cones_unbroken_since_ = -1;       // the cone updates have come without a gap since then
  bool new_cones_ = false;                // since the planner last ran
  std::optional<Stamp> gnss_good_since_;  // stamp of the newest good fix
  bool gnss_good_ = false;
  std::optional<Stamp> map_matched_;  // stamp of the newest match of the pose to the cone map

  // Real-time planning.
  std::optional<Path> plan_;
  std::vector<Obstacle> obstacles_;  // the cone map as the body must avoid it (refreshed with the cones)
  Stamp last_plan_attempt_ = -1e9;
  PlanService* plan_service_ = nullptr;
  bool plan_pending_ = false;  // a plan is out with the service
  bool discard_plan_ = false;  // ... made before a loop closure moved the map: dropped when it comes
  bool planner_stalled_ = false;
  struct PlanOutcome {  // of the plan() call of this cycle, for step()'s output
    bool planned = false, ok = false, one_boundary = false, colour_blind = false, cut_short = false;
  } plan_outcome_;

  // Following.
  std::vector<double> lap_times_;
  double odometer_ = 0;
  std::optional<Vec2> last_position_;
  double last_steering_ = 0;
  double progress_s_ = 0;
  PathSource last_source_ = PathSource::None;
};

}  // namespace fsd
