#pragma once
// One mission's part of driving, behind one small interface, so that the Autopilot keeps only what every mission
// shares (real-time planner, path followers, AS supervisor) and each mission can be tested alone, without a car.
// Per control cycle the Autopilot calls, in this order:
//   start(in)              once, at the first cycle in AS Driving with a state: the mission is laid out from here
//   update_path(in)        cones (and the real-time plan) in; the path to follow out
//   progress(in, follow)   in AS Driving, after following: lap events and faults out, maybe the finish
//   limit(in, command)     the mission's own limits on the follower's command (the stop after the finish, ...)
//   request(in)            in AS Driving, after supervision: an AS transition the mission asks for itself
// The missions: control/mission_trackdrive (trackdrive, autocross), mission_acceleration (acceleration, EBS
// test), mission_skidpad, mission_inspection. Like every core they do no I/O and read no clock.
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "common/types.hpp"
#include "control/autopilot_config.hpp"
#include "control/planning/path.hpp"

namespace fsd {

enum class PathSource { None, Planner, Recorded, Skidpad, Straight };
std::string_view to_string(PathSource s);

// The lap path (lap 2 on) when it was built: what became of the recorded lap-1 line.
struct LapLineBuilt {
  double length = 0;        // m
  double closure_gap = 0;   // m from the recorded lap's end to its start
  double recentre_rms = 0;  // m: how far the line moved onto the mapped centre line
  double clearance = 0;     // m: the least clearance of the body from a mapped cone round the lap
};

// One line for the log: "lap path built: 181.9 m, closed within 0.12 m, moved 0.21 m (RMS) onto the centre
// line, the body at least 0.14 m from every cone".
std::string to_string(const LapLineBuilt& l);

// What the Autopilot knows in this cycle. The pointers stay valid for the call only.
struct MissionInput {
  Stamp now = 0;
  const VehicleState* state = nullptr;       // the newest fused state; null before the first
  const std::vector<Cone>* cones = nullptr;  // the newest cone map (map frame); never null from the Autopilot
  std::uint64_t cones_seq = 0;               // counts the cone maps received: a new one when it changes
  Stamp cones_stamp = -1;                    // time of the newest cone map
  Stamp cones_unbroken_since = -1;           // cone maps have come without a gap since then
  const Path* plan = nullptr;                // the newest real-time plan (missions that use the planner)
  bool plan_ok = false;                      // the planner made that plan in this cycle
  bool gnss_ok = false;                      // a good GNSS fix within control.gnss_timeout
  bool gnss_seen = false;                    // a good GNSS fix ever (without satellites: never)
  bool map_matched = false;                  // the pose matched to the cone map within control.map_match_timeout
  double odometer = 0;                       // m driven since the first state
  double progress_s = 0;                     // m: arc length of the car on the path it last followed
};

// A fault for the supervisor's log (AsSupervisor::report): logged once while `active` stays true.
struct MissionFault {
  std::string source, what, action;
  bool active = true;
};

// The path to follow this cycle.
struct MissionPath {
  const Path* path = nullptr;  // valid until the next call; null: nothing to follow yet
  PathSource source = PathSource::None;
  bool fixed = false;     // a path of the mission's own exists (lane, figure of eight, run-out): it counts as a
                          // plan for the supervisor's watchdog
  bool replaced = false;  // the mission's own path was replaced: the follower starts afresh
  std::optional<double> resume_s;  // ... near this far along the new path, when the mission knows
  std::vector<MissionFault> faults;
};

// What happened after following.
struct MissionEvents {
  std::vector<LapEvent> laps;            // laps (skid pad circles, acceleration runs) completed, in order
  std::optional<LapLineBuilt> lap_line;  // a new recorded lap path: its follower starts afresh
  std::vector<MissionFault> faults;
};

class MissionRun {
 public:
  explicit MissionRun(const AutopilotConfig& config) : config_(config) {}
  virtual ~MissionRun() = default;

  // Trackdrive and autocross drive on the real-time planner's path (MissionInput::plan).
  virtual bool uses_planner() const { return false; }
  // The supervisor watches cone maps and plans (all but inspection, which stands on its jacks).
  virtual bool needs_perception() const { return true; }
  // Live tuning: from the next call on.
  virtual void set_config(const AutopilotConfig& config) { config_ = config; }

  virtual void start(const MissionInput& in);
  virtual MissionPath update_path(const MissionInput& in) = 0;
  // `follow` is the follower's result this cycle, null when there was no path to follow.
  virtual MissionEvents progress(const MissionInput& in, const FollowResult* follow) = 0;
  // After the finish: brake to a stop within the mission's stop distance.
  virtual void limit(const MissionInput& in, ControlCommand& command) const;
  virtual AsRequest request(const MissionInput&) { return AsRequest::None; }
  // A loop closure corrected the localization: what the mission holds in the map frame, placed by poses estimated
  // so far, moves by `correction(instant of the pose)` (map ← estimated). Nothing by default.
  virtual void relocate(const std::function<Pose2(Stamp)>& /*correction*/, Stamp /*now*/) {}

  bool started() const { return started_; }
  bool finished() const { return finished_; }  // past the finish (stopping or stopped)
  Stamp start_time() const { return start_time_; }
  const Pose2& start_pose() const { return start_pose_; }

 protected:
  // The finish: the stop after it brakes from the speed of now to a standstill within `stop_distance`.
  void finish(const MissionInput& in, double stop_distance);
  // The target speed on the way to that standstill (+inf before the finish).
  double stop_cap(const MissionInput& in, double decel) const;

  AutopilotConfig config_;
  bool started_ = false;
  Stamp start_time_ = 0;
  Pose2 start_pose_;

 private:
  bool finished_ = false;
  double finish_speed_ = 0, finish_odometer_ = 0, stop_distance_ = 0;
};

// Mission::None: no path, no laps, never finished (the car is held).
class NoMission final : public MissionRun {
 public:
  using MissionRun::MissionRun;
  MissionPath update_path(const MissionInput&) override { return {}; }
  MissionEvents progress(const MissionInput&, const FollowResult*) override { return {}; }
};

}  // namespace fsd
