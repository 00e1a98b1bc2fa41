#pragma once
// The driving brain in one object, for the daemon's control thread: takes the newest VCU status, cone map,
// fused vehicle state and GNSS quality, and each cycle returns the command for the VCU and the AS request.
// Inside: the mission (trackdrive, autocross, acceleration, skid pad, inspection, EBS test), real-time midline
// planning, the lap-2 trajectory, the lap counter, the path follower and the AS supervisor. No I/O, no threads:
// the caller owns time (every call carries the stack's clock) and calls from one thread.
//
// One control cycle (on each GNSS-INS sample or at 50–100 Hz):
//   on_vcu(status)          the newest VcuStatus
//   on_cones(t, map)        only when mapping produced a new cone map (map frame, all cones so far; ~10 Hz)
//   on_state(state)         the fused VehicleState (map frame; steering = measured wheel angle)
//   on_gnss(t, good)        the newest GNSS-INS sample's GnssSample::good
//   plan(now)               the real-time planner, when new cones arrived or replan_period passed (≈ 0.2–0.5 ms)
//   out = step(now)         send out.command to the VCU every cycle, out.request while it is not None;
//                           out.path / out.follow / out.lap / faults() feed telemetry and the scorecard.
// plan() and step() are separate calls so that the caller can time each (the core reads no clock). Lap 2's path
// (built once, 10–30 ms) is built inside step() unless a LapBuildService is set: the daemon on the car hands it to
// a worker so that the control cycle keeps its period, and takes the lap when it is ready.
#include <optional>
#include <string_view>
#include <vector>

#include "common/track.hpp"
#include "common/types.hpp"
#include "control/as_supervisor.hpp"
#include "control/follower.hpp"
#include "control/lap2_config.hpp"
#include "control/lap_build_service.hpp"
#include "control/lap_counter.hpp"
#include "control/midline_planner.hpp"
#include "control/missions.hpp"
#include "control/recorded_trajectory.hpp"
#include "control/skidpad.hpp"

namespace fsd {

struct AutopilotConfig {
  MidlinePlannerConfig planner;
  FollowerConfig follower;
  SpeedConfig speed;
  MissionConfig mission;
  SupervisorConfig supervisor;
  LapCounterConfig laps;
  RecordedTrajectoryConfig trajectory;
  Lap2Config lap2;
  double replan_period = 0.1;  // s: the real-time plan is refreshed at least this often (on new cones at once)
  double gnss_timeout = 0.5;   // s without a good GNSS fix: lap 2 falls back to real-time planning
};

enum class PathSource { None, Planner, Recorded, Skidpad, Straight };
std::string_view to_string(PathSource s);

// The lap path (lap 2 on) when it was built: what became of the recorded lap-1 line.
struct LapLineBuilt {
  double length = 0;        // m
  double closure_gap = 0;   // m from the recorded lap's end to its start
  double recentre_rms = 0;  // m: how far the line moved onto the mapped centre line
  int tight_turns = 0;      // turns re-shaped to the steering lock
};

// One line for the log: "lap path built: 181.9 m, closed within 0.12 m, moved 0.21 m (RMS) onto the centre
// line, 1 tight turn(s)".
std::string to_string(const LapLineBuilt& l);

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
  bool plan_tight_turn = false;          // that plan shaped a turn to the steering lock
  std::optional<LapLineBuilt> lap_line;  // the lap path was built this cycle
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

  // The real-time planner at time `now`, when it is due (new cones, or replan_period since the last attempt);
  // returns whether it ran. Call before step() in each cycle of a mission that plans (trackdrive, autocross).
  bool plan(Stamp now);
  // One control cycle at time `now` (≥ the newest input stamp): runs the mission, follows, supervises. Always
  // returns a command; outside AS Driving it holds the car.
  ControlOutput step(Stamp now);

  // Read-outs for telemetry and the scorecard.
  Mission mission() const { return mission_; }
  const Path* realtime_path() const { return plan_ ? &*plan_ : nullptr; }
  const Path* recorded_path() const { return lap_path_ ? &*lap_path_ : nullptr; }
  const std::vector<Fault>& faults() const { return supervisor_.faults(); }
  const std::vector<double>& lap_times() const { return lap_times_; }
  const std::vector<Cone>& cones() const { return cones_; }
  const std::optional<SkidpadGeometry>& skidpad() const { return skidpad_; }
  bool open_end_seen() const { return run_out_.has_value(); }  // an open layout's end is in sight
  AsState as_state() const { return supervisor_.as_state(); }
  const AutopilotConfig& config() const { return config_; }

  // Live tuning: the planner, follower, speed and supervisor settings take effect from the next step.
  void set_config(const AutopilotConfig& config);
  // Lap 2's path built by `service` (which must outlive the autopilot) instead of inside step(); null: inside step().
  void set_lap_builder(LapBuildService* service) { lap_builder_ = service; }
  // Fault injection (tests, the virtual car): the planner produces nothing while stalled.
  void set_planner_stalled(bool stalled) { planner_stalled_ = stalled; }

 private:
  void start_mission(Stamp now);
  void update_mission(Stamp now, const FollowResult* last_follow, ControlOutput& out);
  void finish(Stamp now);
  void detect_open_end(Stamp now);
  // Metres from the nose to the nearest cone across the acceleration straight ahead (within the car's width and a
  // margin of the line): the braking zone's closing row, once seen.
  std::optional<double> cone_across_straight() const;
  const Path* select_path(Stamp now, PathSource& source);
  SpeedLimits lap2_limits() const;
  // Lap 2's path from lap 1's poses in [t0, t1] (and the plan `ahead` of an early build): built now, or handed to
  // the lap builder and taken by take_lap_build() once ready.
  void build_lap(Stamp now, Stamp t1, std::vector<Vec2> ahead, ControlOutput& out);
  void take_lap_build(Stamp now, ControlOutput& out);
  void use_lap_build(Stamp now, const TrajectoryResult& built, ControlOutput& out);
  bool uses_planner() const { return mission_ == Mission::Trackdrive || mission_ == Mission::Autocross; }
  int target_laps() const { return mission_ == Mission::Autocross ? 1 : config_.mission.laps; }

  AutopilotConfig config_;
  Mission mission_;
  ColourConvention convention_;
  MidlinePlanner planner_;
  PathFollower follower_;
  PathFollower lap2_follower_;  // on the recorded lap path (its own gains)
  AsSupervisor supervisor_;
  RecordedTrajectory trajectory_;

  // Newest inputs.
  std::optional<VehicleState> state_;
  std::vector<Cone> cones_;
  Stamp cones_stamp_ = -1;
  Stamp cones_unbroken_since_ = -1;  // the cone updates have come without a gap since then
  bool new_cones_ = false;
  std::optional<Stamp> gnss_good_since_;  // stamp of the newest good fix
  bool gnss_good_ = false;

  // Real-time planning.
  std::optional<Path> plan_;
  Stamp last_plan_attempt_ = -1e9;
  bool planner_stalled_ = false;
  struct PlanOutcome {  // of the plan() call of this cycle, for step()'s output
    bool planned = false, ok = false, one_boundary = false, colour_blind = false, tight_turn = false;
  } plan_outcome_;

  // Mission state.
  bool started_ = false;
  Pose2 start_pose_;
  std::optional<LapCounter> lap_counter_;
  std::optional<Stamp> lap1_start_;
  std::optional<Path> lap_path_;
  std::vector<SpeedZone> lap_zones_;  // its profile's speed caps (tight turns)
  LapBuildService* lap_builder_ = nullptr;
  bool build_pending_ = false;     // a job is out with the lap builder
  bool pending_early_ = false;     // the pending build is the early one (before the line)
  std::optional<Stamp> lap1_end_;  // lap 1's crossing, once it happened
  std::optional<Path> straight_;
  double straight_start_s_ = 0;
  std::optional<Stamp> straight_timing_start_;
  std::optional<SkidpadGeometry> skidpad_;
  std::optional<SkidpadPlan> skidpad_plan_;
  std::optional<Path> entry_;
  std::optional<Path> run_out_;  // open layout: the last plan, then straight on to a stop past the end line
  double open_end_s_ = 0;        // arc length of the end line on run_out_
  int skidpad_mark_ = 0;
  std::optional<Stamp> skidpad_mark_time_;
  std::vector<double> lap_times_;
  bool finished_ = false;
  double finish_speed_ = 0, finish_odometer_ = 0, stop_distance_ = 0;
  double odometer_ = 0;
  std::optional<Vec2> last_position_;
  Stamp mission_start_ = 0;
  double last_steering_ = 0;
  double progress_s_ = 0;
  PathSource last_source_ = PathSource::None;
};

}  // namespace fsd
