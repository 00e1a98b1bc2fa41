#include "daemon/stack/stack.hpp"

#include <time.h>

#include <chrono>
#include <deque>
#include <mutex>
#include <numbers>
#include <span>
#include <stdexcept>

#include "common/bounded_queue.hpp"
#include "common/logging.hpp"
#include "common/params.hpp"
#include "common/thread_cpu.hpp"
#include "common/track.hpp"
#include "control/control_config.hpp"
#include "daemon/dds/dds_settings.hpp"
#include "daemon/feeders/truth_frames.hpp"
#include "daemon/stack/cone_classifier_file.hpp"
#include "daemon/stack/fused_localization.hpp"
#include "daemon/stack/gnss_state.hpp"
#include "daemon/stack/lap_build_thread.hpp"
#include "daemon/stack/lidar_localization.hpp"
#include "daemon/stack/loop_solve_thread.hpp"
#include "daemon/stack/plan_thread.hpp"
#include "daemon/stack/scan_processor.hpp"
#include "daemon/stack/settings.hpp"
#include "daemon/stack/step_log.hpp"
#include "daemon/telemetry/dashboard_view.hpp"
#include "drivers/vlp16/scan_builder.hpp"
#include "localization/cone_map.hpp"
#include "localization/loop_closure/loop_closure_config.hpp"
#include "localization/map_match.hpp"
#include "localization/pose_history.hpp"
#include "perception/truth_perception.hpp"

namespace fsd {

namespace {

constexpr int kTelemetryEvery = 4;                 // control cycles between dashboard snapshots (25 Hz at 100 Hz)
constexpr std::size_t kMaxLinkFaults = 256;        // VCU link events kept for the report
constexpr std::size_t kMaxGnssPending = 256;       // samples decoded between two cycles (50 Hz: one or two)
constexpr std::size_t kCameraFramesKept = 4;       // the newest camera frames, for the one nearest each scan (20 Hz)
constexpr std::size_t kPosesKept = 512;            // the localization's poses: over 2 s at 100 Hz + 50 Hz
constexpr std::size_t kRemoteFramesKept = 8;       // dds: perception frames between two cycles (10 Hz: one)
constexpr std::uint64_t kScanFailuresLogged = 10;  // scans whose processing failed, logged one by one

double steady_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

}  // namespace

struct Stack::Impl {
  StackOptions opt;
  RunSettings run;
  std::string localization_source;  // run.localization_source as it applies to this run
  std::string perception_source;    // run.perception_source as it applies to this run
  std::optional<Pose2> first_pose;
  ColourConvention convention;
  std::shared_ptr<spdlog::logger> log = logger("stack");
  StepLog step_log{logger("run")};
  std::function<double()> wall;
  std::function<double()> cpu;

  // Decoders.
  Vlp16Config vlp_cfg;
  std::unique_ptr<Vlp16ScanBuilder> lidar;
  std::shared_ptr<const Scan> last_scan;
  Stamp last_scan_end = 0;  // its last firing
  bool new_scan = false;
  PositionPacketParser position;
  PpsState pps = PpsState::Absent;
  std::unique_ptr<GnssDriver> gnss;
  std::vector<GnssSample> gnss_pending;
  std::unique_ptr<VcuSession> vcu;
  std::shared_ptr<const std::vector<std::uint8_t>> last_jpeg;
  struct CameraJpeg {
    Stamp capture;
    std::shared_ptr<const std::vector<std::uint8_t>> jpeg;
  };
  std::deque<CameraJpeg> camera_recent;  // bounded by kCameraFramesKept
  std::uint64_t camera_frames = 0, camera_decode_failures = 0;
  std::optional<Stamp> last_camera_frame;  // arrival of the newest frame

  // The simulator's truth (truth sources).
  std::optional<TruthStateFrame> truth;
  std::vector<Cone> truth_cones;
  bool truth_scan = false;
  std::uint64_t truth_rejected = 0;

  // Perception and mapping.
  TruthPerception truth_perception;
  bool detects = false;                         // the lidar and lidar_camera sources: the stages on each scan
  bool camera_stage = false;                    // lidar_camera: and the camera stage
  PoseHistory poses{kPosesKept};                // the localization's, for deskew, accumulation and the camera
  std::unique_ptr<FusedLocalization> fused;     // the fused and lidar_odometry (satellites denied) sources
  std::unique_ptr<LidarLocalization> odometry;  // the LiDAR odometry's scans, its increments into `fused`
  // The scans' stages (perception, the odometry's scan match): touched only through the jobs handed to them, one
  // scan at a time, on the processing thread (StackOptions::scan_worker; declared after the processor, so it goes
  // first) or inside the step.
  std::unique_ptr<ScanProcessor> processor;
  std::unique_ptr<FixedLatencyJobThread<ScanResult>> scan_worker;
  std::optional<ScanResult> scan_done;  // without the worker: the scan processed in this step
  bool scan_waiting = false;            // a scan not handed over yet (the newest; one it replaced is skipped)
  bool scan_out = false;                // a scan handed over, its result not taken yet
  double scan_handed_wall = 0;          // the wall time of the cycle that handed it over (end to end)
  std::uint64_t scans_skipped = 0, scan_failures = 0;
  LidarCameraCounters detector_counters;  // as of the newest processed scan
  double perceived_from = 0;              // this cycle: the wall time its perception frame's latency counts from
  Stamp odometry_vcu_stamp = -1e300;      // the newest VCU status the odometry has taken
  std::function<void(const lidar_odometry::OdometryOutput&)> odometry_hook;
  std::uint64_t perception_frames = 0;
  struct RemoteFrame {
    ConeDetections detections;
    std::vector<Cone> camera_rejected;
  };
  std::deque<RemoteFrame> remote_frames;  // dds: bounded by kRemoteFramesKept
  double remote_max_age = 0;              // dds.max_detection_age
  std::uint64_t remote_late = 0;
  std::uint64_t map_poses_applied = 0;  // fused: cone-map matches the filter took while no GNSS fix was recent
  ConeMap cone_map;
  MapMatchConfig map_match;                               // the pose drawn towards the cone map
  std::unique_ptr<loop_closure::LoopCloser> loop_closer;  // lidar_odometry: each lap's loop on the start's cones
  std::unique_ptr<LoopSolveThread> loop_worker;           // real time: the loop's solve off the control thread
  double loop_step_s = 0;  // the control thread's time of the closing frame whose solve is out
  std::vector<LoopClosureRecord> loop_closures;
  std::function<void(const LoopClosureRecord&)> loop_closure_hook;
  Stamp step_now = 0;  // the cycle's time: the paced workers' run clock
  std::shared_ptr<const ConeDetections> last_detections;
  std::shared_ptr<const LabelledCloud> last_cloud;  // the sensor sources' split of the newest scan
  std::function<void(const ConeDetections&, const Pose2&)> detections_hook;

  // Control.
  AutopilotConfig control;
  std::unique_ptr<LapBuildThread> lap_worker;
  std::unique_ptr<PlanThread> plan_worker;
  std::unique_ptr<Autopilot> autopilot;
  std::optional<VehicleState> state;
  DashboardView view;
  Duration plan_budget = 0;
  std::uint64_t late_plans = 0;

  // Feeder hooks.
  std::vector<StackTap*> taps;
  std::vector<StackTap*> snapshot_taps;  // those of `taps` that want the snapshots
  ParamRegistry* params = nullptr;
  std::shared_ptr<BoundedQueue<ParamChange>> changed_keys = std::make_shared<BoundedQueue<ParamChange>>(1024);
  std::uint64_t changes_dropped = 0;
  Telemetry* telemetry = nullptr;
  std::function<void(TelemetrySnapshot&)> telemetry_extras;
  RunMetrics* metrics = nullptr;
  std::function<void(CycleFigures&)> metrics_extras;

  // Results.
  std::map<std::string, LatencyStats> latency;
  StackCycle cycle;
  std::uint64_t cycles = 0;
  mutable std::mutex link_m;
  std::vector<FaultRecord> link_faults;  // guarded by link_m: the VCU link's threads report here too
  mutable std::mutex counters_m;
  StackCounters counters;  // guarded by counters_m, refreshed at the end of each cycle

  Impl(const Config& cfg, StackOptions o)
      : opt(std::move(o)),
        run(run_section().read(cfg)),
        convention(ColourConvention::named(run.colours)),
        wall(opt.wall_clock ? opt.wall_clock : steady_seconds),
        cpu(opt.cpu_clock ? opt.cpu_clock : thread_cpu_seconds),
        vlp_cfg(read_vlp16_config(cfg)),
        truth_perception(truth_perception_section().read(cfg), static_cast<std::uint64_t>(run.seed) * 31 + 5),
        cone_map(cone_map_section().read(cfg)),
        map_match(map_match_section().read(cfg)),
        view(opt.mission, opt.laps) {
    // The car has no ground truth: the truth sources stand for what the car has (its perception stages, with the
    // camera when it is calibrated; the GNSS-INS pose), and the log says so.
    localization_source = run.localization_source;
    if (!opt.simulator && localization_source == "truth") {
      localization_source = "gnss";
      log->info("no ground truth on the car: run.localization_source = truth drives on the GNSS-INS pose");
    }
    if (localization_source == "fused") fused = std::make_unique<FusedLocalization>(cfg);
    if (localization_source == "lidar_odometry") {
      fused = std::make_unique<FusedLocalization>(cfg, FusedLocalization::Satellites::Denied);
      const StartPose start = start_pose_section().read(cfg);
      log->info(
          "localization: without satellites, from x {:.2f} y {:.2f} yaw {:.3f}: the LiDAR odometry, the wheels "
          "and the gyro fused, held to the cone map",
          start.x, start.y, start.yaw);
    }
    if (fused && fused->takes_lidar_odometry()) odometry = std::make_unique<LidarLocalization>(cfg);
    // Only without satellites does the pose drift without bound: the fused pose is held by GNSS-INS fixes, the
    // truth and gnss sources have nothing to close.
    if (localization_source == "lidar_odometry") {
      const auto lc = loop_closure::read_loop_closure_config(cfg);
      if (lc.enabled) loop_closer = std::make_unique<loop_closure::LoopCloser>(lc);
      if (loop_closer && opt.loop_closure_worker) {
        loop_worker = std::make_unique<LoopSolveThread>();
        if (opt.paced_workers) loop_worker->pace_by([this] { return step_now; });
      }
    }
    perception_source = run.perception_source;
    if (!opt.simulator && perception_source == "truth") {
      perception_source = opt.camera ? "lidar_camera" : "lidar";
      log->info("no ground truth on the car: run.perception_source = truth runs the {} stages", perception_source);
    }
    // The default on a car without a calibrated camera: the LiDAR stages alone, said loudly (not a refusal, so a car
    // whose camera is not fitted yet still starts).
    if (perception_source == "lidar_camera" && !opt.camera) {
      perception_source = "lidar";
      log->warn(
          "run.perception_source = lidar_camera without the camera's calibration (drivers.camera.calibration): "
          "LiDAR-only detections, colour from reflectivity");
    }
    std::unique_ptr<LidarCameraDetector> detector;
    if (perception_source == "lidar" || perception_source == "lidar_camera") detector = make_detector(cfg);
    detects = detector != nullptr;
    camera_stage = detector && detector->has_camera();
    if (detector || odometry) {
      processor = std::make_unique<ScanProcessor>(
          std::move(detector), odometry ? make_odometry(cfg, vlp_cfg.body_from_sensor()) : nullptr, wall);
      if (opt.scan_worker) {
        scan_worker = std::make_unique<FixedLatencyJobThread<ScanResult>>(ScanResult::failed);
        if (opt.paced_workers) scan_worker->pace_by([this] { return step_now; }, run.scan_latency);
      }
    }
    if (perception_source == "dds") {
      remote_max_age = dds::dds_section().read(cfg).max_detection_age;
      log->info("perception: frames of a perception process over DDS (late after {:.2f} s)", remote_max_age);
    }

    lidar = std::make_unique<Vlp16ScanBuilder>(vlp_cfg, [this](Scan&& scan) {
      last_scan_end = firing_span(scan).last;
      last_scan = std::make_shared<const Scan>(std::move(scan));
      new_scan = true;
      if (scan_waiting && processor) ++scans_skipped;
      scan_waiting = true;
    });
    gnss = std::make_unique<GnssDriver>(read_gnss_config(cfg), [this](const GnssSample& s) {
      if (gnss_pending.size() < kMaxGnssPending) gnss_pending.push_back(s);
    });
    vcu = std::make_unique<VcuSession>(vcu_section().read(cfg), opt.start,
                                       [this](const VcuLinkEvent& e) { on_link_event(e); });
    vcu->set_mission(opt.mission);

    control = opt.control ? *opt.control : read_control(cfg);
    control.mission.laps = opt.laps;
    plan_budget = control.planner.time_budget;
    autopilot = std::make_unique<Autopilot>(control, opt.mission, convention);
    if (opt.lap_build_worker) {
      lap_worker = std::make_unique<LapBuildThread>();
      if (opt.paced_workers) lap_worker->pace_by([this] { return step_now; });
      autopilot->set_lap_builder(lap_worker.get());
    }
    if (opt.plan_worker) {
      plan_worker = std::make_unique<PlanThread>();
      if (opt.paced_workers) plan_worker->pace_by([this] { return step_now; }, plan_budget);
      autopilot->set_plan_service(plan_worker.get());
    }
    if (opt.worker_priority > 0) {
      std::optional<std::string> failed;
      const auto realtime = [&](auto& worker) {
        if (worker && !failed) failed = worker->set_realtime(opt.worker_priority);
      };
      realtime(scan_worker);
      realtime(processor);
      realtime(plan_worker);
      realtime(lap_worker);
      realtime(loop_worker);
      if (failed) log->warn("the workers stay at normal scheduling: {}", *failed);
    }
  }

  std::unique_ptr<LidarCameraDetector> make_detector(const Config& cfg) {
    std::unique_ptr<CameraStage> camera;
    if (perception_source == "lidar_camera") {
      const CameraStageConfig cc = read_camera_stage_config(cfg);
      camera =
          std::make_unique<CameraStage>(opt.camera->calibration, load_cone_classifier_model(cc.classifier.model), cc);
    }
    log->info("perception: {} (LiDAR mount x {:.2f} y {:.2f} z {:.2f} m)", perception_source, vlp_cfg.mount.x,
              vlp_cfg.mount.y, vlp_cfg.mount.z);
    return std::make_unique<LidarCameraDetector>(read_lidar_detector_config(cfg), vlp_cfg.body_from_sensor(),
                                                 std::move(camera));
  }

  void on_link_event(const VcuLinkEvent& e) {
    switch (e.kind) {
      case VcuLinkEventKind::StatusRestored:
      case VcuLinkEventKind::PortRestored:
        logger("vcu")->info("{} (gap {:.3f} s)", describe(e), e.gap);
        break;
      default:
        logger("vcu")->warn("{}", describe(e));
        break;
    }
    std::lock_guard lock(link_m);
    if (link_faults.size() < kMaxLinkFaults)
      link_faults.push_back({e.t, "vcu", describe(e), "supervisor watchdog", std::nullopt});
  }

  void decode(const RawFrame& f) {
    switch (f.channel) {
      case RawChannel::Vlp16Data:
        lidar->on_data_packet(f.t, f.bytes);
        break;
      case RawChannel::Vlp16Position: {
        PositionPacket p;
        if (position.parse(f.bytes, p) == PositionStatus::Ok) pps = p.pps;
        break;
      }
      case RawChannel::Nmea:
        gnss->feed(f.bytes, f.t);
        break;
      case RawChannel::Camera:
        // Kept as the camera sent it (JPEG) for the dashboard; the camera stages decode what they use.
        last_jpeg = std::make_shared<const std::vector<std::uint8_t>>(f.bytes.begin(), f.bytes.end());
        ++camera_frames;
        last_camera_frame = f.t;
        if (camera_stage) {
          if (camera_recent.size() == kCameraFramesKept) camera_recent.pop_front();
          camera_recent.push_back({f.t - opt.camera->latency, last_jpeg});
        }
        break;
      case RawChannel::VcuRx:
        vcu->on_bytes(f.t, f.bytes);
        break;
      case RawChannel::VcuTx:
        break;  // what the stack sent: recorded, nothing to decode
      case RawChannel::TruthState:
        if (auto s = decode_truth_state(f.bytes))
          truth = *s;
        else
          ++truth_rejected;
        break;
      case RawChannel::TruthCones:
        if (auto c = decode_truth_cones(f.bytes))
          truth_cones = std::move(*c);
        else
          ++truth_rejected;
        break;
      case RawChannel::TruthScan:
        truth_scan = true;
        break;
      case RawChannel::TruthLidarReturns:
        break;  // which cones the LiDAR could see: recorded for the scorecard, nothing the stack may use
    }
  }

  // Live parameter changes, on the Stack's thread: each changed key's current value into the typed config through
  // its section's member pointer. After an overflow of the queue every tunable key is applied again.
  void apply_param_changes(Stamp now) {
    if (!params) return;
    bool any = false;
    const std::uint64_t dropped = changed_keys->dropped();
    if (dropped != changes_dropped) {
      changes_dropped = dropped;
      while (changed_keys->try_pop()) {}
      for (const auto& p : params->list()) any |= apply_control_param(control, p.entry->key, p.value);
    }
    while (auto change = changed_keys->try_pop()) {
      if (auto v = params->get(change->key)) any |= apply_control_param(control, change->key, *v);
      for (auto* tap : taps) tap->on_param(now, *change);
    }
    if (!any) return;
    control.mission.laps = opt.laps;
    plan_budget = control.planner.time_budget;
    autopilot->set_config(control);
  }

  // The perception source's frame, when one is due: detections (vehicle frame) into the map, the map to control.
  // (The lidar and lidar_camera sources' frames come with their scans' processing: take_scan.)
  bool perceive(Stamp now) {
    if (detects) return false;
    if (perception_source == "dds") return perceive_remote(now);
    const bool due = new_scan || truth_scan;
    new_scan = truth_scan = false;
    if (!due || !truth) return false;
    // The ideal detector sees from the true pose; its detections (vehicle frame) are placed in the map by the
    // localization's pose of the same instant, as a real detector's are.
    const std::optional<Pose2> placed = poses.at(now);
    if (!placed) return false;
    const double w0 = wall();
    ConeDetections det = truth_perception.detect(now, truth_cones, truth->state.pose);
    map_detections(now, std::move(det), *placed, {}, wall() - w0);
    return true;
  }

  // One perception frame's detections, taken at `pose`, into the map and the map to control; `stage_s`: the
  // detector's time (wall clock), to which the mapping's is added for latency_ms.perception.
  void map_detections(Stamp now, ConeDetections det, Pose2 pose, std::span<const Cone> camera_rejected,
                      double stage_s) {
    const double w0 = wall();
    if (fused) {
      // Each frame is matched to the cone map (a match: the pose agrees with the map, which keeps lap 2 on the
      // recorded lap through a GNSS loss); while no GNSS fix is recent (always, without satellites), the match's
      // whole alignment goes into the filter as a measurement (the cones mapped so far hold the pose where the
      // odometry and the wheels alone drift).
      if (const auto m = match_to_map(det.cones, pose, cone_map.cones(), map_match)) {
        autopilot->on_map_match(now);
        if (!fused->gnss_recent()) {
          if (const auto moved =
                  fused->add_map_correction(m->alignment, map_match.fused_sigma, map_match.fused_yaw_sigma)) {
            pose = *moved * pose;
            ++map_poses_applied;
          }
        }
      }
    }
    cone_map.update(det, pose, camera_rejected);
    double closing = 0;  // the loop closer's time is not perception's
    if (loop_closer) {
      const double w = wall();
      close_loop(now, det, pose);
      closing = wall() - w;
      latency["loop_closure"].add(closing);
    }
    autopilot->on_cones(now, cone_map.cones());
    const double dt = stage_s + (wall() - w0 - closing);
    latency["perception"].add(dt);
    cycle.figures.perception_s = dt;
    if (detections_hook) detections_hook(det, pose);  // the scorecard's, outside the stage's time
    last_detections = std::make_shared<const ConeDetections>(std::move(det));
    ++perception_frames;
  }

  // The frame to the loop closer; when it closes the lap's loop, the lap's graph solved: on the worker (its result
  // taken by a later step, collect_loop_closure) or here.
  void close_loop(Stamp now, const ConeDetections& det, const Pose2& pose) {
    const double w0 = wall();
    auto solve = loop_closer->feed(det.stamp, pose, det.cones);
    if (!solve) return;
    LoopSolveJob job = [s = std::move(*solve), wall = wall] {
      const double w = wall();
      SolvedLoop out{loop_closure::solve_loop(s)};
      out.solve_s = wall() - w;
      return out;
    };
    if (loop_worker && loop_worker->submit(job)) {
      loop_step_s = wall() - w0;
      return;
    }
    const SolvedLoop solved = job();
    finish_loop(now, solved, wall() - w0, false);
  }

  // The worker's solve, when it is done: applied before this cycle's localization, so that the cycle runs on the
  // corrected pose and map. Its time is the loop closer's (latency_ms.loop_closure), not this step's.
  void collect_loop_closure(Stamp now) {
    if (!loop_worker) return;
    const auto solved = loop_worker->poll();
    if (!solved) return;
    latency["loop_closure"].add(solved->solve_s);
    if (finish_loop(now, *solved, loop_step_s, true)) autopilot->on_cones(now, cone_map.cones());
  }

  // A solve's result to the closer. When it closes the loop, the correction goes to everything placed by the poses
  // estimated so far: the odometry's output from now on, the pose history, the cone map, the autopilot's state,
  // plan and recorded lap-1 poses. Poses estimated after the closing frame (while the solve was out) move with the
  // newest keyframe's correction (correction_at). `step_s`: the control thread's time of the closing frame.
  bool finish_loop(Stamp now, const SolvedLoop& solved, double step_s, bool on_worker) {
    const double w0 = wall();
    const auto closed = loop_closer->finish(solved.result);
    if (!closed) return false;
    const auto at = [&closed](Stamp t) { return closed->correction_at(t); };
    fused->relocate(closed->correction);
    poses.correct(at);
    const int merged = cone_map.correct(at);
    autopilot->relocate(at, now);
    if (state) {
      state->pose = at(state->stamp) * state->pose;
      autopilot->on_state(*state);
    }
    LoopClosureRecord r;
    r.t = closed->t;
    r.lap = closed->lap;
    r.estimate = closed->keyframes.back().estimate;
    r.correction = closed->correction;
    r.pairs = closed->pairs;
    r.rms = closed->rms;
    r.keyframes = int(closed->keyframes.size());
    r.cones_merged = merged;
    r.solve_s = solved.solve_s;
    r.control_s = step_s + (wall() - w0);
    log->info(
        "loop {} closed at {:.2f} s on {} start cones (rms {:.2f} m): moved x {:.2f} y {:.2f} m yaw {:.2f} deg, "
        "{} keyframes, {} cones merged, solved in {:.0f} ms ({}), control thread {:.1f} ms",
        r.lap, r.t, r.pairs, r.rms, r.correction.x, r.correction.y, r.correction.yaw * 180 / std::numbers::pi,
        r.keyframes, merged, r.solve_s * 1e3, on_worker ? "worker" : "in the step", r.control_s * 1e3);
    loop_closures.push_back(r);
    if (loop_closure_hook) loop_closure_hook(r);
    return true;
  }

  // dds: the perception process's frames since the last cycle, each placed by this process's pose of its instant
  // (the stamps carry across). One older than dds.max_detection_age is late: counted, not used.
  bool perceive_remote(Stamp now) {
    bool any = false;
    while (!remote_frames.empty()) {
      RemoteFrame f = std::move(remote_frames.front());
      remote_frames.pop_front();
      if (now - f.detections.stamp > remote_max_age) {
        ++remote_late;
        continue;
      }
      const auto pose = poses.at(f.detections.stamp);
      if (!pose) continue;
      map_detections(now, std::move(f.detections), *pose, f.camera_rejected, 0.0);
      any = true;
    }
    return any;
  }

  // The scans' processing: a result that is due taken first (which frees the worker), then the newest scan handed
  // over; without the worker it is processed at once and taken in this same step.
  bool process_scans(Stamp now, double w_step) {
    if (!processor) return false;
    bool perceived = take_scan(now);
    if (hand_over_scan(w_step)) perceived |= take_scan(now);
    return perceived;
  }

  // The newest scan to the stages with copies of what they need. Perception waits for a pose to place it by.
  bool hand_over_scan(double w_step) {
    if (!scan_waiting || !last_scan || scan_out) return false;
    ScanJob job;
    job.scan = last_scan;
    job.odometry = odometry && odometry->takes(*last_scan);
    if (job.odometry) job.measured = odometry->motion_over(*last_scan);
    job.detect = detects && !poses.empty();
    if (!job.odometry && !job.detect) return false;
    if (job.detect) {
      job.poses = poses;
      if (const CameraJpeg* c = camera_jpeg_near(last_scan_end)) {
        job.camera_jpeg = c->jpeg;
        job.camera_capture = c->capture;
      }
    }
    scan_waiting = false;
    scan_handed_wall = w_step;
    scan_out = true;
    if (scan_worker) {
      if (!scan_worker->submit(
              [p = processor.get(), job = std::move(job)]() mutable { return p->process(std::move(job)); }))
        scan_out = false;  // not reached: one scan out at a time
      return scan_out;
    }
    try {
      scan_done = processor->process(std::move(job));
    } catch (const std::exception& e) {
      scan_done = ScanResult::failed(e);
    }
    return true;
  }

  // A processed scan, once due: the odometry's output into the localization, the detections into the map.
  bool take_scan(Stamp now) {
    if (!scan_out) return false;
    std::optional<ScanResult> r = scan_worker ? scan_worker->poll() : std::exchange(scan_done, std::nullopt);
    if (!r) return false;
    scan_out = false;
    if (!r->failure.empty()) {
      if (++scan_failures <= kScanFailuresLogged)
        log->error("a scan's processing failed ({} so far; the next scan is processed as usual): {}", scan_failures,
                   r->failure);
      return false;
    }
    if (r->camera_decode_failed) ++camera_decode_failures;
    if (r->detector_counters) detector_counters = *r->detector_counters;
    if (r->odometry) take_odometry(*r->odometry, r->odometry_s);
    if (!r->detection) return false;
    LidarDetection& d = *r->detection;
    const std::optional<Pose2> pose = poses.at(d.detections.stamp);
    if (!pose) return false;
    last_cloud = std::make_shared<const LabelledCloud>(
        LabelledCloud{d.detections.stamp, std::move(d.ground_points), std::move(d.obstacle_points)});
    perceived_from = scan_handed_wall;
    map_detections(now, std::move(d.detections), *pose, d.camera_rejected, r->perception_s);
    return true;
  }

  // The odometry's output for a scan: its increment into the fusion filter, and the state again, replacing one as
  // old (the same instant estimated again with the scan).
  void take_odometry(const lidar_odometry::OdometryOutput& out, double stage_s) {
    latency["odometry"].add(stage_s);
    odometry->accept(out);
    if (odometry_hook) odometry_hook(out);
    const auto increment = odometry->increment();
    if (!increment) return;
    fused->add({}, std::nullopt, increment);
    if (const auto v = fused->state(vcu_steering()); v && (!state || v->stamp >= state->stamp)) set_state(*v);
  }

  // The camera frame taken nearest `t`; none without a camera stage or a frame.
  const CameraJpeg* camera_jpeg_near(Stamp t) const {
    if (camera_recent.empty()) return nullptr;
    const CameraJpeg* best = &camera_recent.front();
    for (const auto& c : camera_recent)
      if (std::abs(c.capture - t) < std::abs(best->capture - t)) best = &c;
    return best;
  }

  // This cycle's measurements into the localization (the scans' odometry comes with their processing: take_scan).
  void localize() {
    const double steering = vcu_steering();
    // The car's measured motion (GNSS-INS yaw rate, rear wheels) deskews and predicts the odometry's scans.
    if (odometry) {
      for (const auto& s : gnss_pending)
        if (s.yaw_rate_valid) odometry->add_motion(s.stamp, std::nullopt, s.yaw_rate);
      if (const auto st = vcu->status(); st && st->stamp > odometry_vcu_stamp) {
        odometry_vcu_stamp = st->stamp;
        odometry->add_motion(st->stamp, st->rear_axle_speed(), std::nullopt);
      }
    }
    for (const auto& s : gnss_pending) {
      // Without satellites the receiver's fixes are not the pose's: lap 2 is anchored by the cone map alone.
      if (!(fused && fused->satellites_denied())) autopilot->on_gnss(s.stamp, s.good);
      if (localization_source == "gnss" && gnss_pose_usable(s, gnss->origin().has_value()))
        set_state(state_from_gnss(s, steering));
    }
    if (fused) {
      fused->add(gnss_pending, vcu->status());
      if (const auto v = fused->state(steering); v && (!state || v->stamp > state->stamp)) set_state(*v);
    }
    gnss_pending.clear();
    if (localization_source == "truth" && truth) set_state(truth->state);
  }

  // The localization's state: to the autopilot and into the pose history.
  void set_state(const VehicleState& v) {
    state = v;
    autopilot->on_state(v);
    poses.add(v.stamp, v.pose);
  }

  double vcu_steering() const {
    const auto st = vcu->status();
    return st ? st->steering_measured : 0.0;
  }

  const StackCycle& step(Stamp now) {
    step_now = now;
    for (auto* tap : taps) tap->on_cycle(now);
    cycle = {};
    ++cycles;
    if (const auto st = vcu->status()) autopilot->on_vcu(*st);
    // The camera stage's frames: the supervisor watches for a camera that stops (control.supervisor.camera_timeout).
    if (camera_stage && last_camera_frame) autopilot->on_camera(*last_camera_frame);
    if (opt.simulator && truth) autopilot->set_planner_stalled(truth->planner_stalled);
    const double w_perception = wall();
    perceived_from = w_perception;
    collect_loop_closure(now);
    localize();  // first: the sensor sources place this cycle's scan by the newest pose
    if (state && !first_pose) first_pose = state->pose;
    cycle.perceived = process_scans(now, w_perception);
    cycle.perceived |= perceive(now);
    apply_param_changes(now);

    const double w0 = wall(), c0 = cpu();
    const bool planned = autopilot->plan(now);
    const double w1 = wall(), c1 = cpu();
    cycle.out = autopilot->step(now);
    const double w2 = wall();
    const ControlOutput& out = cycle.out;
    step_log.update(out, autopilot->faults());
    vcu->set_command(out.command, now);
    vcu->set_as_request(out.request);
    const double w3 = wall();
    for (auto* tap : taps) tap->on_output(now, out.command, out.request);

    CycleFigures& fig = cycle.figures;
    fig.t = now;
    if (planned) {
      fig.planning_s = w1 - w0;
      latency["planning"].add(fig.planning_s);
      // Wall time includes the time the thread waited for a core (a loaded desk: 100s of ms); the plan's own
      // cost is its CPU time, and that is what the budget is about.
      // On the plan worker the plan's own CPU time is the worker's; here only its hand-over.
      const double cost = plan_worker ? plan_worker->last_cpu_s() : c1 - c0;
      fig.planning_cpu_s = cost;
      latency["planning_cpu"].add(cost);
      fig.late_plan = cost > plan_budget;
      if (fig.late_plan) note_late_plan(now, cost, fig.planning_s);
    }
    fig.control_s = w2 - w1;
    latency["control"].add(fig.control_s);
    if (cycle.perceived) {
      fig.end_to_end_s = w3 - perceived_from;
      latency["end_to_end"].add(fig.end_to_end_s);
    }
    fig.planned = out.planned;
    fig.plan_one_boundary = out.plan_one_boundary;
    fig.plan_colour_blind = out.plan_colour_blind;
    fig.plan_cut_short = out.plan_cut_short;
    fig.as_state = as_state();
    fig.laps = static_cast<int>(autopilot->lap_times().size());

    std::optional<Vec2> position;
    if (state) position = state->pose.position();
    view.on_cycle(now, fig.as_state, out, autopilot->lap_times().size(), position, cycles);
    publish(now);
    refresh_counters();
    return cycle;
  }

  // One late plan is a warning: the plan is used, the count goes to /metrics, the log says it (at most once a
  // second). The supervisor stops the car only when no usable plan arrived for control.supervisor.plan_timeout.
  Stamp last_late_log = -1e9;
  void note_late_plan(Stamp now, double cpu_s, double wall_s) {
    ++late_plans;
    if (now - last_late_log < 1.0) return;
    last_late_log = now;
    log->warn("plan took {:.1f} ms CPU, {:.1f} ms wall (budget {:.1f} ms): late, used ({} late so far)", cpu_s * 1e3,
              wall_s * 1e3, plan_budget * 1e3, late_plans);
  }

  void publish(Stamp now) {
    if (metrics) {
      CycleFigures fig = cycle.figures;
      if (metrics_extras) metrics_extras(fig);
      metrics->on_cycle(fig);
    }
    if ((!telemetry && snapshot_taps.empty()) || cycles % kTelemetryEvery != 0) return;
    TelemetrySnapshot s = view.snapshot(now, as_state(), cycle.out, *autopilot, vcu->status());
    if (state) {
      s.state = *state;
      // The newest scan, placed by the estimated pose at its last firing and the configured mount (car.lidar.*).
      if (last_scan) {
        s.scan = last_scan;
        s.lidar_pose = poses.at(last_scan_end).value_or(state->pose).to_pose3() * vlp_cfg.body_from_sensor();
      }
    }
    if (last_cloud) {
      s.cloud = last_cloud;
      s.cloud_pose = poses.at(last_cloud->stamp).value_or(state ? state->pose : Pose2{}).to_pose3();
    }
    s.detections = last_detections;
    if (last_detections) s.detections_pose = poses.at(last_detections->stamp);
    s.camera_jpeg = last_jpeg;
    if (state) s.localization = localization_view();
    for (const auto& r : loop_closures)
      s.loop_closures.push_back({r.t, r.lap, r.estimate.x, r.estimate.y, r.correction.x, r.correction.y,
                                 r.correction.yaw, r.pairs, r.rms, r.cones_merged});
    if (telemetry_extras) telemetry_extras(s);
    view.add_truth_path(s);
    const auto shared = std::make_shared<const TelemetrySnapshot>(std::move(s));
    for (auto* tap : snapshot_taps) tap->on_snapshot(shared);
    if (telemetry) telemetry->publish(shared);
  }

  // The dashboard's view of the localization: its source, and with the fused source the filter's own verdict and
  // covariance.
  web::LocalizationView localization_view() const {
    web::LocalizationView v;
    v.t = state->stamp;
    v.source = localization_source;
    if (fused) {
      const auto e = fused->estimate();
      v.quality = std::string(fusion::to_string(e.quality));
      v.gnss = std::string(fusion::to_string(e.gnss));
      v.has_covariance = e.initialised;
      v.covariance = e.covariance;
    }
    return v;
  }

  AsState as_state() const {
    const auto st = vcu->status();
    return st ? st->as_state : AsState::Off;
  }

  std::vector<FaultRecord> faults() const {
    std::vector<FaultRecord> all;
    {
      std::lock_guard lock(link_m);
      all = link_faults;
    }
    for (const auto& f : autopilot->faults()) all.push_back({f.t, f.source, f.what, f.action, f.cleared});
    return all;
  }

  void refresh_counters() {
    std::lock_guard lock(counters_m);
    counters.lidar = lidar->decode_counters();
    counters.scans = lidar->frames();
    counters.lidar_lost_packets = lidar->lost_packets();
    counters.position = position.counters();
    counters.pps = pps;
    counters.gnss = gnss->counters();
    counters.vcu = vcu->counters();
    counters.camera_frames = camera_frames;
    counters.camera_decode_failures = camera_decode_failures;
    counters.perception_frames = perception_frames;
    counters.camera_verified = detector_counters.camera.verified;
    counters.camera_rejected = detector_counters.camera.rejected;
    counters.scans_skipped = scans_skipped;
    counters.scan_failures = scan_failures;
    counters.truth_frames_rejected = truth_rejected;
    counters.remote_frames_late = remote_late;
    counters.map_poses_applied = map_poses_applied;
    counters.cycles = cycles;
    counters.late_plans = late_plans;
  }
};

Stack::Stack(const Config& config, StackOptions options) : impl_(std::make_unique<Impl>(config, std::move(options))) {}
Stack::~Stack() = default;

void Stack::feed(const RawFrame& frame) {
  for (auto* tap : impl_->taps) tap->on_frame(frame);
  impl_->decode(frame);
  impl_->refresh_counters();  // cheap (a lock and a copy): the counters never lag the frames taken
}

void Stack::feed_remote_detections(ConeDetections detections, std::vector<Cone> camera_rejected) {
  auto& q = impl_->remote_frames;
  if (q.size() == kRemoteFramesKept) q.pop_front();
  q.push_back({std::move(detections), std::move(camera_rejected)});
}

VcuSession& Stack::vcu() { return *impl_->vcu; }
void Stack::report_link_event(const VcuLinkEvent& e) { impl_->on_link_event(e); }
const StackCycle& Stack::step(Stamp now) { return impl_->step(now); }

void Stack::add_tap(StackTap* tap) {
  if (!tap) return;
  impl_->taps.push_back(tap);
  if (tap->wants_snapshots()) impl_->snapshot_taps.push_back(tap);
}

void Stack::set_params(ParamRegistry* params) {
  impl_->params = params;
  if (params) params->subscribe([q = impl_->changed_keys](const ParamChange& c) { q->push(c); });
}

void Stack::set_telemetry(Telemetry* telemetry, std::function<void(TelemetrySnapshot&)> extras) {
  impl_->telemetry = telemetry;
  impl_->telemetry_extras = std::move(extras);
}

void Stack::set_metrics(RunMetrics* metrics, std::function<void(CycleFigures&)> extras) {
  impl_->metrics = metrics;
  impl_->metrics_extras = std::move(extras);
}

void Stack::on_detections(std::function<void(const ConeDetections&, const Pose2&)> hook) {
  impl_->detections_hook = std::move(hook);
}

void Stack::on_loop_closure(std::function<void(const LoopClosureRecord&)> hook) {
  impl_->loop_closure_hook = std::move(hook);
}

void Stack::on_odometry(std::function<void(const lidar_odometry::OdometryOutput&)> hook) {
  impl_->odometry_hook = std::move(hook);
}

Mission Stack::mission() const { return impl_->opt.mission; }
int Stack::laps() const { return impl_->opt.laps; }
const Autopilot& Stack::autopilot() const { return *impl_->autopilot; }
Autopilot& Stack::autopilot() { return *impl_->autopilot; }
const std::vector<Cone>& Stack::cone_map() const { return impl_->autopilot->cones(); }
const std::optional<VehicleState>& Stack::state() const { return impl_->state; }
AsState Stack::as_state() const { return impl_->as_state(); }
std::vector<FaultRecord> Stack::faults() const { return impl_->faults(); }
const std::map<std::string, LatencyStats>& Stack::latencies() const { return impl_->latency; }
const std::vector<LoopClosureRecord>& Stack::loop_closures() const { return impl_->loop_closures; }

StackCounters Stack::counters() const {
  std::lock_guard lock(impl_->counters_m);
  return impl_->counters;
}
std::optional<Pose2> Stack::first_pose() const { return impl_->first_pose; }
const ColourConvention& Stack::convention() const { return impl_->convention; }

}  // namespace fsd
