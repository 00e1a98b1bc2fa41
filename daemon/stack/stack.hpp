#pragma once
// The one Stack (DESIGN.md §3–4): raw frames in, the VCU command stream and telemetry out. Every decoder and every
// stage of the pipeline is here, wired once: the VLP-16 scan builder and position-packet parser, the NMEA driver,
// the VCU protocol session; perception, localization and mapping behind run.perception_source and
// run.localization_source; the autopilot (planning, missions, following, supervision); the dashboard's view.
// Three feeders drive it: the car's driver threads (daemon/hardware_run), the virtual car's lockstep or real-time
// loop (daemon/sim_run) and the replayer of a recording. They own the transports, threads and clocks; the Stack
// owns none of them but its workers (StackOptions): the processing thread of the LiDAR scans (perception and the
// odometry's scan match: ScanProcessor), lap 1's plans, the lap-2 build and the loop closure's solve.
//
// One thread (the feeder's control thread) calls everything, in this order each control cycle:
//   feed(frame) ...       every raw frame that arrived since the last cycle, in arrival order
//   vcu().tick(...)       (lockstep feeders) the VCU Command due now; on the car the link's sender thread does it
//   step(now)             one control cycle: sources, mapping, planning, control, the command to the VCU session
// With the workers, step() never waits for them (but in a paced run, below): it hands a job over and takes its
// result at a later cycle. A scan's detections and odometry are then taken a cycle or two after it completed
// (latency_ms.end_to_end counts from the cycle that handed it over).
// Taps see the frames and cycles in exactly this order, so replaying a recording repeats the run.
//
// Sources:
//   perception    truth: the ideal detector on the simulator's standing cones (RawChannel::TruthCones), run on
//                 each LiDAR scan or, without a simulated LiDAR, on each TruthScan tick.
//                 lidar: the LiDAR stages on each VLP-16 scan, deskewed and accumulated by the localization's poses;
//                 lidar_camera: and the camera stage on the camera frame nearest the scan (StackOptions::camera).
//                 dds: the frames of a perception process elsewhere (split mode, feed_remote_detections), each used
//                 once, unless older than dds.max_detection_age when taken (late: counted, not used, so a late
//                 perception is the silent LiDAR's fault).
//   localization  truth: the simulator's state (RawChannel::TruthState); gnss: the GNSS-INS pose as reported;
//                 fused: GNSS-INS, wheel speeds (and the LiDAR odometry's increments) through a fusion filter;
//                 lidar_odometry: without satellites, the same filter on the LiDAR odometry's increments, the
//                 wheels and the gyro, from the start pose (localization.start.*), held to the cone map.
//   Detections of every perception source are placed in the map by the localization's pose of their instant.
//   With lidar_odometry each lap's loop is closed on the start's cones (localization.loop_closure.*): from then on
//   the pose is corrected, the cone map and the recorded lap-1 poses are moved with the lap's solved pose graph
//   (solved on the loop-closure worker in real time: applied at a later step to all estimated since).
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "common/camera_geometry.hpp"
#include "common/config.hpp"
#include "common/latency_stats.hpp"
#include "common/track.hpp"
#include "common/types.hpp"
#include "control/autopilot.hpp"
#include "daemon/stack/fault_record.hpp"
#include "daemon/stack/loop_closure_record.hpp"
#include "daemon/stack/raw_frame.hpp"
#include "daemon/telemetry/run_metrics.hpp"
#include "daemon/telemetry/telemetry.hpp"
#include "drivers/gnss/gnss_driver.hpp"
#include "drivers/vcu/vcu_session.hpp"
#include "drivers/vlp16/decoder.hpp"
#include "drivers/vlp16/position_packet.hpp"
#include "localization/lidar_odometry/lidar_odometry.hpp"

namespace fsd {

class ParamRegistry;

struct StackOptions {
  Mission mission = Mission::Trackdrive;
  int laps = 2;                      // trackdrive laps (run.laps, or --laps)
  bool lap_build_worker = false;     // lap 2 built on a thread of the Stack's (real time); else inside the step
  bool plan_worker = false;          // lap 1's real-time plans so; else inside the step
  bool loop_closure_worker = false;  // the loop's solve so (that thread reads wall_clock: the solve's time)
  bool scan_worker = false;          // the scans' processing (perception, the odometry's scan match) so
  // (wall_clock is read on that thread too, and on the processor's own for the scan match: the stages' figures)
  // > 0: the workers' threads under SCHED_FIFO at this priority (below the control thread's: daemon.realtime_priority)
  int worker_priority = 0;
  // The feeder runs faster than real time (a headless simulation with workers): a once-a-lap job's result is taken
  // once as much run time has passed as the job took on the wall clock, the step waiting while the run is ahead of
  // it (JobServiceThread::pace_by), so that the car drives on meanwhile as long as on the car, not for seconds; a
  // plan's control.planner.time_budget and a scan's run.scan_latency after its hand-over (FixedLatencyJobThread).
  bool paced_workers = false;
  bool simulator = false;  // the feeder sends the simulator's truth frames (the truth sources need them)
  Stamp start = 0;         // the run clock when the VCU session starts waiting for its first status
  // The control settings when the caller has them typed already (the tests' harness); else the configuration's.
  std::optional<AutopilotConfig> control;
  // The camera the camera stage sees through (perception_source = lidar_camera): its calibration and the time from
  // capture to a frame's arrival (subtracted from the frame's receive time).
  struct Camera {
    CameraCalibration calibration;
    double latency = 0.0;
  };
  std::optional<Camera> camera;
  // Wall-clock seconds for the compute-time figures (latencies, late plans); never used for a decision. Read from
  // the workers' threads as well. Empty: std::chrono::steady_clock.
  std::function<double()> wall_clock;
  // CPU seconds of the calling thread: what a plan cost, without the time the thread waited for a core on a busy
  // machine. A late plan is judged on it. Empty: CLOCK_THREAD_CPUTIME_ID.
  std::function<double()> cpu_clock;
};

// Decoder counters, for the feeders' stats line and report (a copy, safe to take from any thread).
struct StackCounters {
  DecodeCounters lidar;
  std::uint64_t scans = 0, lidar_lost_packets = 0;
  PositionCounters position;
  PpsState pps = PpsState::Absent;  // in the newest accepted position packet
  GnssCounters gnss;
  VcuSessionCounters vcu;
  std::uint64_t camera_frames = 0;
  std::uint64_t camera_decode_failures = 0;  // frames the camera stage could not decode (skipped: LiDAR only)
  std::uint64_t perception_frames = 0;       // perception frames run (scans, or truth ticks)
  std::uint64_t remote_frames_late = 0;      // dds: perception frames too old when taken (not used)
  std::uint64_t map_poses_applied = 0;       // fused: poses from the cone map taken while no GNSS fix was recent
  std::uint64_t camera_verified = 0, camera_rejected = 0;  // candidates the camera stage accepted / removed
  std::uint64_t truth_frames_rejected = 0;
  std::uint64_t cycles = 0;
  std::uint64_t late_plans = 0;  // plans whose CPU time exceeded control.planner.time_budget (a warning)
  std::uint64_t scans_skipped = 0;  // scans not processed: the processing thread was busy until a newer one came
  std::uint64_t scan_failures = 0;  // scans whose processing threw (logged; the next scan is processed as usual)
};

// What one control cycle did.
struct StackCycle {
  ControlOutput out;
  CycleFigures figures;    // for /metrics
  bool perceived = false;  // a perception frame ran this cycle
};

class Stack {
 public:
  // Throws std::invalid_argument naming the key for a source the run cannot have (lidar_camera without a camera),
  // and ClassifierModelError / std::runtime_error for a camera model that cannot be read.
  Stack(const Config& config, StackOptions options);
  ~Stack();
  Stack(const Stack&) = delete;
  Stack& operator=(const Stack&) = delete;

  // The one input. Bad frames are counted by their decoder and otherwise ignored.
  void feed(const RawFrame& frame);
  // run.perception_source = dds: one perception frame of the perception process (daemon/dds/remote_perception),
  // stamped on this run's clock; taken by the next step. Bounded: the oldest goes when frames pile up.
  void feed_remote_detections(ConeDetections detections, std::vector<Cone> camera_rejected);
  // The VCU protocol session whose Commands the feeder sends: tick() in lockstep, the link's sender on the car.
  // Thread-safe.
  VcuSession& vcu();
  // One control cycle at `now` on the run's clock (≥ every frame fed so far). The result is valid until the next.
  const StackCycle& step(Stamp now);

  // A fault of the VCU link's transport (the serial port lost, back): recorded with the session's own. Any thread.
  void report_link_event(const VcuLinkEvent& e);

  // Feeder hooks, set before the first frame; each must outlive the Stack's use of it.
  void add_tap(StackTap* tap);
  void set_params(ParamRegistry* params);  // live tuning: changes apply at the start of the next step
  // The dashboard: a snapshot every 4th cycle (25 Hz) and the figures of every cycle, handed over without
  // waiting; `extras` add what only the feeder knows (the simulator's truth) before they go.
  void set_telemetry(Telemetry* telemetry, std::function<void(TelemetrySnapshot&)> extras = {});
  void set_metrics(RunMetrics* metrics, std::function<void(CycleFigures&)> extras = {});
  // Sees each perception frame: its detections (vehicle frame) and the pose they were placed at (the scorecard).
  void on_detections(std::function<void(const ConeDetections&, const Pose2&)> hook);
  // Sees each scan the LiDAR odometry took (lidar_odometry, or fused with its increments): the scorecard's drift.
  void on_odometry(std::function<void(const lidar_odometry::OdometryOutput&)> hook);
  // Sees each loop closure as it is applied (the scorecard's pose error before and after).
  void on_loop_closure(std::function<void(const LoopClosureRecord&)> hook);

  // Read-outs, on the Stack's thread or after the run.
  Mission mission() const;
  int laps() const;
  const Autopilot& autopilot() const;
  Autopilot& autopilot();
  const std::vector<Cone>& cone_map() const;         // mapped cones, map frame
  std::optional<Pose2> first_pose() const;           // the first pose the Stack had (the run's start, map frame)
  const ColourConvention& convention() const;        // run.colours
  const std::optional<VehicleState>& state() const;  // what the autopilot was given last
  AsState as_state() const;                          // as the VCU reports it
  std::vector<FaultRecord> faults() const;           // the VCU link's, then the supervisor's
  const std::map<std::string, LatencyStats>& latencies() const;
  const std::vector<LoopClosureRecord>& loop_closures() const;
  StackCounters counters() const;  // any thread

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace fsd
