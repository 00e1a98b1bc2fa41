#pragma once
// The virtual car's fault schedule (`sim.faults.*`): windows in which a part of the car, or of the stack, fails,
// so that the stack's reactions can be tested through a whole run. Every fault has the same trigger:
//   lap = 0   the window opens at simulated time at_s;
//   lap = N   the window opens at_s after the car begins lap N by the timekeeper's gates (the truth, as the
//             scorecard times laps), so "on lap 2" holds however long lap 1 took;
//   at_s < 0  the fault is off (the default); duration_s = 0: the window never closes.
// The faults:
//   gnss           the GNSS-INS receiver loses its fix: `no_fix` (quality 0, the INS attitude continues) or
//                  `silent` (no sentences at all)
//   lidar          the VLP-16 sends no packets (without a simulated LiDAR, the daemon's truth perception sees
//                  nothing instead)
//   camera         the camera sends no frames
//   vcu_link       the serial link between the daemon and the VCU is cut both ways: Commands no longer reach the
//                  stand-in (its heartbeat watchdog fires the EBS), Status frames no longer reach the daemon
//   planner_stall  the stack's real-time planner produces nothing (applied by the daemon: the car has no planner)
// Pure: no I/O, no threads, time only from its arguments.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "common/config.hpp"
#include "common/track.hpp"
#include "drivers/sim/world/timing_gates.hpp"

namespace fsd::sim {

enum class FaultKind : std::uint8_t { Gnss = 0, Lidar, VcuLink, PlannerStall, Camera };
inline constexpr std::array<FaultKind, 5> kFaultKinds{FaultKind::Gnss, FaultKind::Lidar, FaultKind::VcuLink,
                                                      FaultKind::PlannerStall, FaultKind::Camera};
std::string_view to_string(FaultKind k);

struct FaultTrigger {
  int lap = 0;              // 0: at_s is simulated time; N ≥ 1: at_s counts from the start of lap N
  double at_s = -1.0;       // negative: the fault is off
  double duration_s = 0.0;  // 0: until the end of the run
  bool enabled() const { return at_s >= 0.0; }
};

struct GnssFaultTrigger : FaultTrigger {
  std::string mode = "no_fix";  // no_fix | silent
};

struct FaultScheduleConfig {
  GnssFaultTrigger gnss;
  FaultTrigger lidar, vcu_link, planner_stall, camera;
  const FaultTrigger& trigger(FaultKind k) const;
};
void describe_fault_schedule(ConfigSchema& schema);
FaultScheduleConfig read_fault_schedule(const Config& cfg);

// A fault's window once its trigger has fired; `end` is +infinity for a window that never closes.
struct FaultWindow {
  Stamp start = 0, end = 0;
  bool contains(Stamp t) const { return t >= start && t < end; }
};

class FaultSchedule {
 public:
  FaultSchedule(const FaultScheduleConfig& config, const Track& track);

  // The true position at each physics step (monotonic time): counts the laps that lap-triggered faults wait for.
  void on_truth(Stamp t, const Vec2& position);

  bool active(FaultKind k, Stamp t) const;
  // The window of a fault whose trigger has fired (for lap triggers: once lap N has begun).
  std::optional<FaultWindow> window(FaultKind k) const;
  bool any_enabled() const;
  const FaultScheduleConfig& config() const { return config_; }
  // Start times of laps 1, 2, ... by the timekeeper's gates.
  const std::vector<Stamp>& lap_starts() const { return lap_starts_; }

 private:
  FaultScheduleConfig config_;
  TimingGates gates_;
  std::optional<Vec2> last_position_;
  Stamp last_t_ = 0;
  std::vector<Stamp> lap_starts_;
};

}  // namespace fsd::sim
