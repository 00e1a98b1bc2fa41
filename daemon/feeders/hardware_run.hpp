#pragma once
// `fsd run` without --sim: the car's own interfaces as one of the Stack's feeders (daemon/stack/stack.hpp, DESIGN.md
// §3–4). One thread per driver; each hands the raw frames it receives to one bounded queue, and a control thread
// at 100 Hz feeds them to the Stack in arrival order and runs one cycle:
//
//   VLP-16 UDP (data, position) ─► UdpReceiver threads ─┐
//   GNSS-INS tty ─► SerialPort thread ──────────────────┤
//   VCU tty ◄─► VcuLink (port thread, 100 Hz sender) ───┼─► frame queue ─► control thread (100 Hz): Stack::feed…, step
//   camera ─► CameraSource thread (JPEG) ───────────────┘                  │
//                                 the Stack's VcuSession ◄─ command, AS request
// The VcuLink's sender writes the Commands from the Stack's session at its own rate. The cones come from the
// Stack's perception stages on the LiDAR (and the camera when calibrated), the pose from the GNSS-INS (or the
// fusion filter), so every mission runs. With a dashboard the Stack hands a snapshot to the telemetry every
// 4th cycle and its figures to /metrics (both without waiting); tuned parameters apply at the next cycle.
// SIGINT/SIGTERM (or, with --until-finished, AS Finished or Emergency) ends the run: the control thread stops, the
// VCU link sends its safe-stop Commands (speed 0, brake) before its port closes, then the other drivers stop.
#include <atomic>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include <nlohmann/json_fwd.hpp>

#include "common/config.hpp"
#include "common/types.hpp"
#include "daemon/cli/run_options.hpp"

namespace fsd {

class ParamRegistry;
class Stack;
class RunMetrics;
class Telemetry;

class HardwareRun {
 public:
  // Checks everything that can be checked before touching the car, throwing std::invalid_argument naming the
  // key: the mission, the serial devices and the camera source exist, the LiDAR's
  // UDP port can be bound (it is bound here).
  HardwareRun(const Config& config, const RunOptions& options);
  ~HardwareRun();
  HardwareRun(const HardwareRun&) = delete;
  HardwareRun& operator=(const HardwareRun&) = delete;

  // Runs until `stop` becomes true or, with --until-finished, the VCU reports AS Finished or Emergency.
  // Returns 0, or 1 with --until-finished when the mission did not end in AS Finished.
  int run(const std::atomic<bool>& stop);
  // After run(): mission, AS state and its transitions, how the run ended, every driver's counters, faults.
  nlohmann::json report() const;
  // The LiDAR's bound UDP port (resolves drivers.vlp16.data_port = 0).
  int lidar_port() const;
  // The dashboard's parts, before run(); each must outlive the run. Null: none (--headless).
  void set_telemetry(Telemetry* telemetry);
  void set_metrics(RunMetrics* metrics);
  const Stack& stack() const;              // after run(): the map, the start pose
  void set_params(ParamRegistry* params);  // live tuning of the autopilot's settings
  // Called by the control thread after each cycle (the service's watchdog, daemon/service/service_notifier.hpp).
  void set_loop_hook(std::function<void()> hook);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace fsd
