#pragma once
// The autopilot's settings, one section per part (control.* keys, control/control_config.hpp). In a header of
// its own because the missions (control/missions/mission_run.hpp) read them too.
#include "control/missions/lap2_config.hpp"
#include "control/missions/lap_counter.hpp"
#include "control/missions/missions.hpp"
#include "control/planning/path_config.hpp"
#include "control/planning/realtime_planner.hpp"
#include "control/planning/recorded_trajectory.hpp"
#include "control/supervisor/as_supervisor.hpp"
#include "control/tracking/contact_guard.hpp"
#include "control/tracking/follower.hpp"

namespace fsd {

struct AutopilotConfig {
  PlannerConfig planner;
  PathConfig path;
  FollowerConfig follower;
  ContactGuardConfig guard;
  SpeedConfig speed;
  MissionConfig mission;
  SupervisorConfig supervisor;
  LapCounterConfig laps;
  RecordedTrajectoryConfig trajectory;
  Lap2Config lap2;
  double replan_period = 0.1;      // s: the real-time plan is refreshed at least this often (on new cones at once)
  double gnss_timeout = 0.5;       // s without a good GNSS fix: lap 2 leaves the recorded lap, unless ...
  double map_match_timeout = 1.0;  // s: ... the pose was matched to the cone map this recently (Stack: fused source)
};

}  // namespace fsd
