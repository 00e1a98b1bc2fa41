#pragma once
// The daemon's half of the virtual car's fault schedule (drivers/sim/fault_schedule.hpp, `sim.faults.*`) in
// `fsd run --sim`. The car itself silences its GNSS-INS, its LiDAR and the VCU link; this adds what only the
// daemon can do, and what the scorecard needs to judge the stack's reaction:
//   - the perception step's input: with the VLP-16 simulated, perception runs on each new scan, so a silent LiDAR
//     really starves the stack; without it (sim.enable_lidar = false, the fast runs), the truth source's scan tick
//     (RawChannel::TruthScan) comes every 100 ms except during the LiDAR outage: the same fault, applied to the
//     perception feed;
//   - the planner stall: inside the window, flagged in the truth state frame (the Stack stalls its planner);
//   - for each injected fault, the truth around it (speed and longitudinal acceleration every cycle from 0.5 s
//     before to 3 s after the window, at most 15 s of window) and the VCU's AS transitions: the scorecard's
//     "injected_faults", from which tests measure the reaction independently of what the stack says it did.
#include <array>
#include <deque>
#include <optional>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "common/types.hpp"
#include "drivers/sim/virtual_car.hpp"

namespace fsd {

class SimFaults {
 public:
  // `lidar_simulated`: sim.enable_lidar (the VLP-16 model runs and feeds the scan builder).
  SimFaults(sim::VirtualCar& car, bool lidar_simulated);

  // After the car advanced to t, before the stack's step: records the truth around the faults.
  void on_cycle(Stamp t);
  // Whether the planner is stalled at t (sim.faults.planner).
  bool planner_stalled(Stamp t) const;
  // Whether the truth source's scan tick is due at t (only without a simulated LiDAR).
  bool truth_scan_due(Stamp t);
  // The scorecard's "injected_faults": one object per enabled fault (empty array when none).
  nlohmann::json report() const;

 private:
  struct Sample {
    Stamp t;
    double speed, ax, distance;
  };
  struct Record {
    bool started = false, done = false;
    std::vector<Sample> trace;
  };

  sim::VirtualCar& car_;
  bool lidar_simulated_;
  Stamp next_perception_ = 0;
  std::deque<Sample> recent_;  // the last 0.5 s, the part of a trace before its window opens
  std::array<Record, sim::kFaultKinds.size()> records_;
};

}  // namespace fsd
