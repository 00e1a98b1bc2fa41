#pragma once
// Lap 2's path built on a thread of its own (Autopilot::set_lap_builder), so that the control thread keeps its
// period: the build takes 10–30 ms, once per run (bench/control_bench BM_LapBuild). The thread is started with the
// object and joined by its destructor, which waits for a build under way (at most a few tens of ms).
#include "control/missions/lap_build_service.hpp"
#include "daemon/stack/job_thread.hpp"

namespace fsd {

class LapBuildThread final : public JobServiceThread<TrajectoryResult> {
 public:
  // A build that throws comes back without a path, the reason its message (failed): the autopilot reports it.
  LapBuildThread() : JobServiceThread(failed) {}

 private:
  static TrajectoryResult failed(const std::exception& e) {
    TrajectoryResult r;
    r.reason = e.what();
    return r;
  }
};

}  // namespace fsd
