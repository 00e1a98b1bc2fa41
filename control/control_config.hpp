#pragma once
// Configuration sections of the control library (keys under "control.*"); see docs/configuration.md once the
// daemon gathers them. Tunable keys can change while the car runs (Autopilot::set_config).
#include <optional>
#include <string>

#include "common/config.hpp"
#include "control/autopilot.hpp"

namespace fsd {

const ConfigSection<PlannerConfig>& planner_section();                // control.planner (lap 1's planner)
const ConfigSection<CorridorWalkConfig>& walk_section();              // control.planner (its corridor walk)
const ConfigSection<PathConfig>& path_section();                      // control.path (every planned path)
const ConfigSection<PathOptimizerConfig>& optimizer_section();        // control.path (its optimizer)
const ConfigSection<ContactGuardConfig>& guard_section();             // control.guard
const ConfigSection<FollowerConfig>& follower_section();              // control.follower
const ConfigSection<SpeedConfig>& speed_section();                    // control.speed
const ConfigSection<MissionConfig>& mission_section();                // control.mission (laps: run.laps)
const ConfigSection<SupervisorConfig>& supervisor_section();          // control.supervisor
const ConfigSection<LapCounterConfig>& lap_counter_section();         // control.laps
const ConfigSection<RecordedTrajectoryConfig>& trajectory_section();  // control.trajectory
const ConfigSection<Lap2Config>& lap2_section();                      // control.lap2
const ConfigSection<AutopilotConfig>& autopilot_section();            // control (loop timing)

// Every control section into a schema, and all of them back into one AutopilotConfig.
void describe_control(ConfigSchema& schema);
AutopilotConfig read_control(const Config& config);
// A live parameter change of a control.* key applied to `c` through its section's member pointer (and to the
// copies other parts keep of it). False for a key that is not control's.
bool apply_control_param(AutopilotConfig& c, const std::string& key, double value);
// The value of a control.* number, integer or boolean key in `c`; nullopt for a key that is not control's.
std::optional<double> control_param(const AutopilotConfig& c, const std::string& key);

}  // namespace fsd
