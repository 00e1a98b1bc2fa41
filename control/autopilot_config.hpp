#pragma once
// The autopilot's settings, one section per part (control.* keys, control/control_config.hpp). In a header of
// its own because the missions (control/mission_run.hpp) read them too.
#include "control/as_supervisor.hpp"
#include "control/follower.hpp"
#include "control/lap2_config.hpp"
#include "control/lap_counter.hpp"
#include "control/midline_planner.hpp"
#include "control/missions.hpp"
#include "control/recorded_trajectory.hpp"

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

}  // namespace fsd
