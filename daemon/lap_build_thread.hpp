#pragma once
// Lap 2's path built on a thread of its own (Autopilot::set_lap_builder), so that the control thread keeps its
// period: the build takes 10–30 ms, once per run (bench/control_bench BM_LapBuild). The thread belongs to the
// future std::async returns: the autopilot holds it until it takes the lap, and its destructor joins it.
#include <future>

#include "control/autopilot.hpp"

namespace fsd {

inline LapBuilder lap_build_thread() {
  return [](LapBuildJob job) { return std::async(std::launch::async, std::move(job)); };
}

}  // namespace fsd
