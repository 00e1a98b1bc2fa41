#pragma once
// The dashboard's view of the stack, the same on the car and in the simulator: the lines driven on lap 1 and
// after it, the running lap time, and the parts of a telemetry snapshot that come from the autopilot and the VCU
// (cone map, paths, AS status, faults). Owned by the control thread; the snapshot it fills is handed over to the
// telemetry without waiting.
#include <cstdint>
#include <optional>
#include <vector>

#include "common/types.hpp"
#include "control/autopilot.hpp"
#include "daemon/telemetry/telemetry.hpp"

namespace fsd {

class DashboardView {
 public:
  // Points kept per driven line: one every 10 control cycles (10 Hz) is 33 minutes of driving.
  static constexpr std::size_t kMaxTrailPoints = 20000;

  DashboardView(Mission mission, int trackdrive_laps) : mission_(mission), trackdrive_laps_(trackdrive_laps) {}

  // Every control cycle. `position`: where the stack has the car (none before its first state).
  void on_cycle(Stamp now, AsState as, const ControlOutput& out, std::size_t laps_done,
                const std::optional<Vec2>& position, std::uint64_t cycle);

  // A snapshot at `now` with the stack's parts filled; the caller adds the state, sensors and truth.
  TelemetrySnapshot snapshot(Stamp now, AsState as, const ControlOutput& out, const Autopilot& autopilot,
                             const std::optional<VcuStatus>& vcu) const;
  // Sim runs, after the feeder added the truth to `s`: the true path while Driving (points 0.1 m apart), handed
  // over as a new pointer only when it grew.
  void add_truth_path(TelemetrySnapshot& s);

 private:
  Mission mission_;
  int trackdrive_laps_;
  std::vector<Vec2> lap1_trail_, later_trail_;
  std::vector<Vec2> truth_trail_;
  std::shared_ptr<const std::vector<Vec2>> truth_trail_sent_;
  // The lap shown: the one being driven (1 on the first lap), after the finish the last one driven.
  int lap_being_driven(bool finished) const;
  // The lap clock: runs while Driving, frozen when the car stopped, after the finish the last lap's time.
  double lap_clock(Stamp now, bool finished) const;

  std::optional<Stamp> lap_started_;    // go, then each line crossing
  std::optional<Stamp> clock_stopped_;  // when the car left Driving (the clock shows the lap until then)
  std::optional<double> last_lap_time_;
  std::size_t laps_done_ = 0;
  bool finished_ = false;
};

}  // namespace fsd
