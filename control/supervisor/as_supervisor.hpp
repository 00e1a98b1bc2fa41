#pragma once
// The autonomous-system supervisor (DESIGN.md §7): follows the AS state the VCU owns, asks for Ready when the
// stack is healthy, lets the car move only in Driving, and watches every input stream and the planner. A stale
// or missing input, a late plan or a missing plan is a fault: the car slows (LiDAR briefly stale) or makes a
// controlled stop — it never keeps driving on a stale command. After a fault stop at standstill, or when a stop
// takes too long, it asks for Emergency; after the mission's finish at standstill, for Finished. Every fault is
// logged once at its onset with time, source, what and action (the scorecard's "faults").
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "common/types.hpp"
#include "common/wire/vcu_protocol.hpp"

namespace fsd {

// What the stack asks of the VCU's AS state machine: the VCU protocol's own request type, so no mapping is needed.
using wire::vcu::AsRequest;

enum class InputStream : std::uint8_t { Lidar = 0, Pose, Gnss, Vcu, Plan, Camera };
std::string_view to_string(InputStream s);

struct Fault {
  Stamp t = 0;
  std::string source;  // "lidar", "pose", "gnss", "vcu", "planning", "mission", ...
  std::string what;
  std::string action;
  std::optional<Stamp> cleared;  // when the condition ended (a sensor came back); empty: it lasted
};

struct SupervisorConfig {
  double lidar_timeout = 0.3;              // s without cone detections: slow down
  double lidar_stop_timeout = 2.0;         // s: controlled stop
  double camera_timeout = 0.5;             // s without a frame, once one came: a fault (LiDAR-only detections)
  double pose_timeout = 0.2;               // s without a pose: controlled stop
  double vcu_timeout = 0.2;                // s without VCU status: controlled stop
  double plan_timeout = 0.5;               // s since the newest usable plan: controlled stop
  double degraded_speed = 3.0;             // m/s cap while the LiDAR is stale
  double standstill_speed = 0.1;           // m/s
  double standstill_time = 0.5;            // s below standstill_speed counts as standing
  double stop_timeout = 10.0;              // s: a controlled stop not at standstill by then asks for Emergency
  double stuck_timeout = 15.0;             // s standing in Driving before the finish: controlled stop
  bool emergency_after_fault_stop = true;  // at standstill after a fault stop, ask for Emergency (EBS)
  int max_faults = 256;                    // the fault log keeps the first ones
};

// What the supervisor allows this cycle.
struct Supervision {
  bool may_move = false;         // AS Driving and no stop: follow the mission's command
  bool controlled_stop = false;  // brake to standstill, steering from the follower if the pose is fresh
  double speed_cap = 0;          // m/s
  AsRequest request = AsRequest::None;
};

class AsSupervisor {
 public:
  explicit AsSupervisor(SupervisorConfig config = {});

  void set_mission(Mission m) { mission_ = m; }
  Mission mission() const { return mission_; }
  // Which streams this mission cannot do without (pose and VCU always).
  void require(InputStream s, bool required);

  void on_vcu(const VcuStatus& status);
  void heartbeat(InputStream s, Stamp t);  // newest data time of a stream (a good GNSS fix for Gnss)
  // A plan attempt: ok plans refresh the plan stream. How long a plan took is the caller's to measure and count
  // (the core reads no clock); the stop comes from plan_timeout, when no usable plan arrived for that long.
  // `why`: what stops the newest plan short, or why it failed (empty: a whole plan); a stop names it.
  void on_plan(Stamp t, bool ok, const std::string& why = {});
  // A fault found elsewhere (the mission's fallbacks); logged once while `active` stays true.
  void report(Stamp t, const std::string& source, const std::string& what, const std::string& action,
              bool active = true);

  // The request sent to the VCU this cycle (the supervisor's or the mission's): an AS Emergency this stack asked for
  // is its own fault's doing, not logged again when the VCU enters it.
  void requested(AsRequest r) { emergency_asked_ = emergency_asked_ || r == AsRequest::Emergency; }
  // One decision per control cycle; `speed` is the car's speed, `finished` the mission's finish.
  Supervision evaluate(Stamp now, double speed, bool finished);

  AsState as_state() const { return status_ ? status_->as_state : AsState::Off; }
  bool stopping() const { return stop_reason_.has_value(); }
  const std::vector<Fault>& faults() const { return faults_; }
  const SupervisorConfig& config() const { return config_; }
  void set_config(const SupervisorConfig& c) { config_ = c; }

 private:
  bool stale(InputStream s, Stamp now, double timeout) const;
  void raise(Stamp t, const std::string& source, const std::string& what, const std::string& action);
  void clear(Stamp t, const std::string& source, const std::string& what);
  void stop(Stamp t, const std::string& source, const std::string& what);
  std::string plan_why() const { return plan_why_.empty() ? "" : ": " + plan_why_; }

  SupervisorConfig config_;
  Mission mission_ = Mission::None;
  std::optional<VcuStatus> status_;
  std::optional<Stamp> last_[6];
  bool required_[6] = {true, true, false, true, true, false};
  std::optional<Stamp> driving_since_;
  std::optional<std::string> stop_reason_;
  Stamp stop_since_ = 0;
  std::optional<Stamp> standing_since_;
  std::vector<Fault> faults_;
  std::vector<std::pair<std::string, std::string>> active_;
  std::string plan_why_;  // the newest plan's reason for failing or ending short
  std::string emergency_what_;  // the VCU's AS Emergency fault while it lasts
  bool emergency_asked_ = false;
};

}  // namespace fsd
