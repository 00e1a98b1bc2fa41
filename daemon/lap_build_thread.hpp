#pragma once
// Lap 2's path built on a thread of its own (Autopilot::set_lap_builder), so that the control thread keeps its
// period: the build takes 10–30 ms, once per run (bench/control_bench BM_LapBuild). The thread is started with the
// object and joined by its destructor, which waits for a build under way (at most a few tens of ms).
#include <condition_variable>
#include <mutex>
#include <optional>
#include <thread>

#include "control/lap_build_service.hpp"

namespace fsd {

class LapBuildThread final : public LapBuildService {
 public:
  LapBuildThread();
  ~LapBuildThread() override;
  LapBuildThread(const LapBuildThread&) = delete;
  LapBuildThread& operator=(const LapBuildThread&) = delete;

  bool submit(LapBuildJob job) override;  // false while a job is still out
  std::optional<TrajectoryResult> poll() override;

 private:
  void run();
  std::mutex m_;
  std::condition_variable cv_;
  std::optional<LapBuildJob> job_;
  std::optional<TrajectoryResult> result_;
  bool busy_ = false, stop_ = false;
  std::thread thread_;
};

}  // namespace fsd
