#include "daemon/feeders/sim_run.hpp"

#include <chrono>
#include <cmath>

#include <nlohmann/json.hpp>

#include "common/clock.hpp"
#include "common/logging.hpp"
#include "control/missions/missions.hpp"
#include "daemon/dds/ros_time.hpp"
#include "daemon/dds/run_dds.hpp"
#include "daemon/feeders/layout_check.hpp"
#include "daemon/feeders/sim_faults.hpp"
#include "daemon/feeders/truth_frames.hpp"
#include "daemon/recording/recorder.hpp"
#include "daemon/scoring/sim_scoring.hpp"
#include "daemon/stack/settings.hpp"
#include "daemon/stack/stack.hpp"
#include "daemon/telemetry/run_metrics.hpp"
#include "daemon/telemetry/sim_truth.hpp"
#include "drivers/camera/camera_calibration.hpp"
#include "drivers/sim/virtual_car.hpp"
#include "localization/fusion/fusion_config.hpp"

namespace fsd {

namespace {

constexpr double kControlPeriod = 0.01;  // s: the control loop runs at 100 Hz

// The Stack's configuration in a simulated run: the GNSS receiver's local frame is the track's map frame (the
// simulated receiver's origin), not the first fix.
Config stack_config(const Config& cfg, const sim::VirtualCarSettings& car, const Pose2& start) {
  Config c = cfg;
  c.set("drivers.gnss.use_first_fix", false, "the virtual car");
  c.set("drivers.gnss.origin_lat_deg", car.gnss.origin_lat_deg, "the virtual car");
  c.set("drivers.gnss.origin_lon_deg", car.gnss.origin_lon_deg, "the virtual car");
  c.set("drivers.gnss.origin_height_m", car.gnss.origin_height_m, "the virtual car");
  // The receiver's latency from epoch to first byte, as a team takes it from the datasheet: unaccounted, every fix
  // is placed 10 ms late (0.2 m at 20 m/s).
  c.set("drivers.gnss.latency_s", car.gnss.latency_s, "the virtual car");
  // Where the car is staged, as a team measures it on the start line: the LiDAR odometry's origin.
  c.set("localization.start.x", start.x, "the virtual car");
  c.set("localization.start.y", start.y, "the virtual car");
  c.set("localization.start.yaw", wrap_angle(start.yaw), "the virtual car");
  return c;
}

Mission mission_of(const RunSettings& run) {
  const auto m = mission_from_string(run.mission);
  if (!m) throw std::invalid_argument("unknown mission '" + run.mission + "'");
  return *m;
}

}  // namespace

struct SimRun::Impl {
  RunSettings run;
  DaemonSettings daemon;
  Mission mission;
  bool headless, until_finished;
  bool real_time;  // paced: not headless, or split mode (a perception process keeps real time)
  Track track;
  sim::VirtualCarSettings car_settings;
  std::unique_ptr<sim::VirtualCar> car;
  std::unique_ptr<SimFaults> faults;
  std::unique_ptr<Stack> stack;
  std::unique_ptr<dds::RunDds> dds;  // dds.enabled or run.perception_source = dds (daemon/dds/run_dds.hpp)
  std::unique_ptr<SimScoring> scoring;
  Scorecard* card = nullptr;                  // scoring's
  std::unique_ptr<Recorder> recorder;         // --record
  std::unique_ptr<LogForwarding> record_log;  // the log lines into the recording (detached before the recorder goes)
  int truth_cones_hit = -1;
  std::shared_ptr<const std::vector<web::TruthCone>> dashboard_truth_cones;  // rebuilt when a cone falls
  int dashboard_cones_hit = -1;
  std::shared_ptr<spdlog::logger> log = logger("run");
  std::function<void()> loop_hook;
  RunMetrics* metrics = nullptr;  // the dashboard's /metrics

  Impl(const Config& cfg, const RunOptions& opt)
      : run(run_section().read(cfg)),
        daemon(daemon_section().read(cfg)),
        mission(mission_of(run)),
        headless(opt.headless),
        until_finished(opt.until_finished),
        real_time(!opt.headless || run.perception_source == "dds") {
    track = load_track(run.track, ColourConvention::named(run.colours));
    if (track.duplicates_dropped > 0)
      log->warn("{}: {} row(s) repeat a cone already listed; each cone is placed once", run.track,
                track.duplicates_dropped);
    car_settings = sim::read_virtual_car_settings(cfg);
    // The simulated RES operator presses go shortly after the rules' 5 s in Ready unless configured otherwise.
    if (car_settings.vcu.res_go_at_s < 0) car_settings.vcu.res_go_at_s = car_settings.vcu.ready_to_drive_s + 0.5;

    StackOptions so;
    so.mission = mission;
    so.laps = run.laps;
    so.simulator = true;
    // In real time the lap-2 build and the loop closure's solve run beside the control loop as on the car; in
    // lockstep inside the step that asks for them, so that a run is the same every time (unless --workers).
    so.lap_build_worker = real_time || opt.workers;
    so.plan_worker = so.lap_build_worker;
    so.loop_closure_worker = so.lap_build_worker;
    so.scan_worker = so.lap_build_worker;
    if (real_time) so.worker_priority = worker_priority(daemon);
    so.paced_workers = headless && opt.workers;
    // The camera stage sees through the virtual camera, calibrated perfectly; its frames arrive after the latency.
    so.camera = StackOptions::Camera{sim::calibration_of(car_settings.camera), car_settings.camera.latency};
    if (run.perception_source != "truth" && !car_settings.run.lidar)
      throw std::invalid_argument("run.perception_source = " + run.perception_source +
                                  " needs the virtual car's LiDAR: sim.enable_lidar is false");
    const bool needs_lidar_odometry =
        run.localization_source == "lidar_odometry" ||
        (run.localization_source == "fused" && fusion::read_fusion_config(cfg).common.lidar_odometry);
    if (needs_lidar_odometry && !car_settings.run.lidar)
      throw std::invalid_argument("run.localization_source = " + run.localization_source +
                                  " with the LiDAR odometry needs the virtual car's LiDAR: sim.enable_lidar is false");
    if (run.perception_source == "lidar_camera" && !car_settings.run.camera)
      log->warn("run.perception_source = lidar_camera with sim.enable_camera = false: LiDAR-only detections");
    const Config used = stack_config(cfg, car_settings, track.start);
    stack = std::make_unique<Stack>(used, so);
    if (const auto why = layout_refusal(track, mission, stack->autopilot().config())) throw std::invalid_argument(*why);

    // The car's sensors hand their bytes straight to the Stack, as the devices' transports would.
    sim::SensorSinks sinks;
    sinks.vcu_status = [this](Stamp t, std::span<const std::uint8_t> b) { stack->feed({RawChannel::VcuRx, t, b}); };
    sinks.gnss = [this](Stamp t, std::span<const std::uint8_t> b) { stack->feed({RawChannel::Nmea, t, b}); };
    dds = dds::RunDds::make(used, true);
    sinks.lidar = [this](Stamp t, std::span<const std::uint8_t> b) {
      stack->feed({RawChannel::Vlp16Data, t, b});
      if (dds) dds->lidar_packet(b);
    };
    sinks.camera = [this, latency = so.camera->latency](Stamp t, std::span<const std::uint8_t> b) {
      stack->feed({RawChannel::Camera, t, b});
      if (dds) dds->camera_frame(t - latency, b);
    };
    car = std::make_unique<sim::VirtualCar>(track, car_settings, static_cast<std::uint64_t>(run.seed), sinks);
    faults = std::make_unique<SimFaults>(*car, car_settings.run.lidar);

    scoring = std::make_unique<SimScoring>(track, mission, run, *stack);
    card = &scoring->card();
    if (!opt.record.empty()) {
      RecordingContents rc;
      rc.config = &used.as_json();
      rc.run = {"sim",        headless, so.mission,         so.laps,
                so.simulator, so.start, so.camera->latency, to_json(so.camera->calibration).dump()};
      rc.track_file = run.track;
      rc.car = web::car_shape_of(read_car(used));
      recorder = std::make_unique<Recorder>(opt.record, record_section().read(cfg), rc, headless);
      stack->add_tap(recorder.get());
      record_log = std::make_unique<LogForwarding>(recorder->log_sink());
    }
  }

  // The simulator's truth for this cycle, as frames: the state, the standing cones when they changed, the ideal
  // detector's scan tick without a simulated LiDAR.
  void feed_truth(Stamp t) {
    TruthStateFrame ts{state_from_truth(car->truth()), faults->planner_stalled(t),
                       static_cast<std::uint32_t>(car->cones_hit()), car->vcu().state()};
    const auto state = encode_truth_state(ts);
    stack->feed({RawChannel::TruthState, t, state});
    if (car->cones_hit() != truth_cones_hit) {
      const auto standing = car->standing_cones();
      truth_cones_hit = car->cones_hit();
      const auto cones = encode_truth_cones(standing);
      scoring->set_truth_cones(standing);
      stack->feed({RawChannel::TruthCones, t, cones});
    }
    if (faults->truth_scan_due(t)) stack->feed({RawChannel::TruthScan, t, {}});
    // Which cones the LiDAR returned points from (recall_visible_15m), recorded so that a replay scores alike.
    if (car_settings.run.lidar) {
      std::vector<TruthLidarReturns> returns;
      for (const auto& r : car->take_lidar_cone_returns())
        returns.push_back({sim::VirtualCar::cone_id(r.cone), static_cast<std::uint32_t>(r.returns), r.t});
      scoring->add_lidar_returns(returns);
      if (!returns.empty()) stack->feed({RawChannel::TruthLidarReturns, t, encode_truth_lidar_returns(returns)});
    }
  }

  // The simulator's ground truth on the dashboard's /truth/* channels, never mixed into the stack's own.
  void add_truth(TelemetrySnapshot& s) {
    s.truth = fsd::truth_state(*car);
    if (!dashboard_truth_cones || car->cones_hit() != dashboard_cones_hit) {
      dashboard_truth_cones = std::make_shared<const std::vector<web::TruthCone>>(fsd::truth_cones(car->world()));
      dashboard_cones_hit = car->cones_hit();
    }
    s.truth_cones = dashboard_truth_cones;
  }

  int run_loop(const std::atomic<bool>& stop) {
    const auto wall0 = std::chrono::steady_clock::now();
    SimulatedClock pace(1.0);
    if (dds) dds->start(*stack, dds::run_epoch(0.0));
    if (real_time) make_control_thread_realtime(daemon);  // the virtual car's loop is the control thread
    Stamp t = 0;
    double stopped_since = -1;
    int cycle = 0;
    log->info("driving {} on {} ({} lap(s)), seed {}, {}", to_string(mission), track.name,
              timed_laps(mission, run.laps), run.seed, real_time ? "real time" : "headless lockstep");
    while (!stop.load(std::memory_order_relaxed)) {
      t = (++cycle) * kControlPeriod;
      if (real_time && !pace.sleep_until(t)) break;
      if (metrics) metrics->on_cycle_start();
      car->advance_to(t);
      faults->on_cycle(t);
      scoring->on_truth(car->truth());
      feed_truth(t);
      stack->vcu().tick(t, [this, t](std::vector<std::uint8_t> bytes) {
        stack->feed({RawChannel::VcuTx, t, bytes});
        car->feed_vcu(t, bytes);
      });
      if (dds) dds->before_step(*stack);
      stack->step(t);
      scoring->after_step(car->vcu().state(), car->cones_hit());
      if (loop_hook) loop_hook();

      // The end of a run: the mission is over and the car stands (Finished or Emergency), or time ran out.
      const AsState as = car->vcu().state();
      const bool resting = car->truth().speed() < 0.05;
      stopped_since = resting ? (stopped_since < 0 ? t : stopped_since) : -1;
      if (until_finished || headless) {
        if (as == AsState::Finished && stopped_since >= 0 && t - stopped_since > 1.0) break;
        if (as == AsState::Emergency && stopped_since >= 0 && t - stopped_since > 1.0) break;
      }
      if (t >= run.max_sim_time) {
        log->warn("giving up after {} s of simulated time", run.max_sim_time);
        break;
      }
    }
    if (dds) {
      dds->stop();
      log->info("{}", dds->summary());
    }
    scoring->finish(std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count());
    const nlohmann::json injected = faults->report();
    card->set_section("injected_faults", injected);
    if (recorder) {
      recorder->add_closing_metadata(std::string(kInjectedFaultsMetadata), {{"json", injected.dump()}});
      recorder->close();
      card->set_section("recording", to_json(recorder->stats()));
    }
    const auto vc = stack->counters().vcu;
    log->info("run over at t = {:.2f} s: AS {}, {} lap(s), {} cone(s) hit, {} VCU commands, {} statuses", t,
              to_string(car->vcu().state()), card->laps_completed(), car->cones_hit(), vc.commands_sent, vc.statuses);
    if (!until_finished) return 0;
    return card->mission_succeeded() ? 0 : 1;
  }
};

SimRun::SimRun(const Config& config, const RunOptions& options) : impl_(std::make_unique<Impl>(config, options)) {}
SimRun::~SimRun() = default;
int SimRun::run(const std::atomic<bool>& stop) { return impl_->run_loop(stop); }
const Scorecard& SimRun::scorecard() const { return *impl_->card; }
void SimRun::set_telemetry(Telemetry* telemetry) {
  impl_->stack->set_telemetry(telemetry, [this](TelemetrySnapshot& s) { impl_->add_truth(s); });
}
void SimRun::set_metrics(RunMetrics* metrics) {
  impl_->metrics = metrics;
  impl_->stack->set_metrics(metrics, [this](CycleFigures& f) { f.cones_hit = impl_->car->cones_hit(); });
  if (metrics && impl_->recorder) impl_->recorder->set_metrics(metrics->registry());
}
void SimRun::set_params(ParamRegistry* params) { impl_->stack->set_params(params); }
void SimRun::set_loop_hook(std::function<void()> hook) { impl_->loop_hook = std::move(hook); }

const Stack& SimRun::stack() const { return *impl_->stack; }

}  // namespace fsd
