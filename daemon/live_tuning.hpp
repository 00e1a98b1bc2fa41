#pragma once
// Live tuning from the dashboard: the parameter registry holds the values engineers set; the control loop copies
// them into its own copy of the configuration and reads the autopilot's settings from it, on its own thread, so
// the autopilot is never touched from the web's.
#include "common/config.hpp"
#include "control/autopilot.hpp"

namespace fsd {

class ParamRegistry;

// Copies every parameter's live value into `tuned` and returns the control settings read from it, with
// `laps` (the run's, which may come from --laps) in place of control.mission.laps.
AutopilotConfig tuned_control(Config& tuned, const ParamRegistry& params, int laps);

}  // namespace fsd
