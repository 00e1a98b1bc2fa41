#include "daemon/sim_run.hpp"

#include <chrono>
#include <cmath>
#include <optional>

#include <nlohmann/json.hpp>

#include "common/clock.hpp"
#include "common/logging.hpp"
#include "common/params.hpp"
#include "control/autopilot.hpp"
#include "control/control_config.hpp"
#include "control/missions.hpp"
#include "daemon/dashboard_view.hpp"
#include "daemon/lap_build_thread.hpp"
#include "daemon/live_tuning.hpp"
#include "daemon/map_score.hpp"
#include "daemon/perception_score.hpp"
#include "daemon/run_metrics.hpp"
#include "daemon/settings.hpp"
#include "daemon/sim_faults.hpp"
#include "daemon/sim_truth.hpp"
#include "daemon/step_log.hpp"
#include "daemon/telemetry.hpp"
#include "daemon/truth_perception.hpp"
#include "drivers/gnss/gnss_driver.hpp"
#include "drivers/sim/virtual_car.hpp"
#include "drivers/vcu/vcu_session.hpp"
#include "drivers/vlp16/scan_builder.hpp"
#include "localization/cone_map.hpp"

namespace fsd {

namespace {

constexpr double kControlPeriod = 0.01;    // s: the control loop runs at 100 Hz

// The stop zone after a mission's last timing line.
double stop_zone(Mission m) {
  switch (m) {
    case Mission::Trackdrive:
    case Mission::Autocross:
    case Mission::Skidpad: return 30.0;
    default: return 100.0;
  }
}

VehicleState state_from_truth(const sim::VehicleTruth& t) {
  VehicleState s;
  s.stamp = t.t;
  s.pose = t.pose;
  s.vx = t.vx;
  s.vy = t.vy;
  s.yaw_rate = t.yaw_rate;
  s.ax = t.ax;
  s.ay = t.ay;
  s.steering = t.steering;
  return s;
}

}  // namespace

struct SimRun::Impl {
  RunSettings run;
  Mission mission = Mission::Trackdrive;
  Track track;
  sim::VirtualCarSettings car_settings;
  std::unique_ptr<sim::VirtualCar> car;
  std::unique_ptr<SimFaults> faults;  // sim.faults: perception input, planner stall, truth around each fault
  std::unique_ptr<VcuSession> vcu;
  std::unique_ptr<GnssDriver> gnss;
  std::unique_ptr<Vlp16ScanBuilder> lidar;
  std::unique_ptr<Autopilot> autopilot;
  ConeMap cone_map;
  TruthPerception perception;
  PerceptionScore perception_score;
  std::unique_ptr<Scorecard> card;
  Telemetry* telemetry = nullptr;
  RunMetrics* metrics = nullptr;
  VehicleState stack_state;  // what the autopilot was given this cycle (the dashboard's /vehicle/state)
  std::shared_ptr<const std::vector<web::TruthCone>> truth_cones;  // rebuilt when a cone falls
  int truth_cones_hit = -1;
  ParamRegistry* params = nullptr;
  std::atomic<bool> params_changed{false};
  Config tuned;  // the configuration with the live parameter values
  bool headless = true, until_finished = false;
  std::shared_ptr<const Scan> last_scan;
  std::shared_ptr<const ConeDetections> last_detections;
  std::shared_ptr<const std::vector<std::uint8_t>> last_image;
  std::unique_ptr<DashboardView> view;
  std::vector<FaultRecord> link_faults;
  std::shared_ptr<spdlog::logger> log = logger("run");
  StepLog step_log{log};

  Impl(const Config& cfg, const RunOptions& opt)
      : run(run_section().read(cfg)),
        cone_map(cone_map_section().read(cfg)),
        perception(truth_perception_section().read(cfg), static_cast<std::uint64_t>(run.seed) * 31 + 5),
        tuned(cfg) {
    headless = opt.headless;
    until_finished = opt.until_finished;
    const auto m = mission_from_string(run.mission);
    if (!m) throw std::invalid_argument("unknown mission '" + run.mission + "'");
    mission = *m;
    track = load_track(run.track, ColourConvention::named(run.colours));
    if (track.duplicates_dropped > 0)
      logger("run")->warn("{}: {} row(s) repeat a cone already listed; each cone is placed once", run.track,
                          track.duplicates_dropped);
    car_settings = sim::read_virtual_car_settings(cfg);
    // The simulated RES operator presses go shortly after the rules' 5 s in Ready unless configured otherwise.
    if (car_settings.vcu.res_go_at_s < 0) car_settings.vcu.res_go_at_s = car_settings.vcu.ready_to_drive_s + 0.5;

    const auto seed = static_cast<std::uint64_t>(run.seed);
    sim::SensorSinks sinks;
    sinks.vcu_status = [this](Stamp t, std::span<const std::uint8_t> b) { vcu->on_bytes(t, b); };
    sinks.gnss = [this](Stamp t, std::span<const std::uint8_t> b) { gnss->feed(b, t); };
    sinks.lidar = [this](Stamp t, std::span<const std::uint8_t> b) { lidar->on_data_packet(t, b); };
    // Camera frames go to the dashboard as the camera sent them (JPEG); perception does not use them yet.
    sinks.camera = [this](Stamp, std::span<const std::uint8_t> b) {
      if (telemetry) last_image = std::make_shared<const std::vector<std::uint8_t>>(b.begin(), b.end());
    };
    car = std::make_unique<sim::VirtualCar>(track, car_settings, seed, sinks);
    faults = std::make_unique<SimFaults>(*car, car_settings.run.lidar);

    vcu = std::make_unique<VcuSession>(vcu_section().read(cfg), 0.0, [this](const VcuLinkEvent& e) {
      link_faults.push_back({e.t, "vcu", describe(e), "supervisor watchdog"});
    });
    vcu->set_mission(mission);

    // The receiver's local frame is the track's map frame: same origin as the simulated GNSS.
    GnssConfig gc = gnss_section().read(cfg);
    gc.use_first_fix = false;
    gc.origin_lat_deg = car_settings.gnss.origin_lat_deg;
    gc.origin_lon_deg = car_settings.gnss.origin_lon_deg;
    gc.origin_height_m = car_settings.gnss.origin_height_m;
    gnss = std::make_unique<GnssDriver>(gc, [this](const GnssSample& s) { autopilot->on_gnss(s.stamp, s.good); });

    lidar = std::make_unique<Vlp16ScanBuilder>(vlp16_section().read(cfg), [this](Scan&& scan) {
      last_scan = std::make_shared<const Scan>(std::move(scan));
    });

    AutopilotConfig ac = read_control(cfg);
    ac.mission.laps = run.laps;
    // In lockstep a slow plan delays no simulated time, and wall-clock checks would make runs unrepeatable.
    if (headless) ac.supervisor.check_plan_time = false;
    autopilot = std::make_unique<Autopilot>(ac, mission, track.convention);
    // In real time the lap-2 build runs beside the control loop as on the car; in lockstep inside the step that
    // asks for it, so that a run is the same every time.
    if (!headless) autopilot->set_lap_builder(lap_build_thread());

    card = std::make_unique<Scorecard>(track, mission, timed_laps(mission, run.laps), stop_zone(mission), run.seed);
    view = std::make_unique<DashboardView>(mission, run.laps);
    // The limits the stack plans with (the scorecard's "vehicle" object).
    card->set_vehicle_limits({ac.speed.mu, ac.speed.a_accel_max, ac.speed.a_brake_max, ac.speed.v_max});
  }

  void publish_telemetry(Stamp t, const ControlOutput& out) {
    if (!telemetry) return;
    TelemetrySnapshot s = view->snapshot(t, car->vcu().state(), out, *autopilot, vcu->status());
    s.state = stack_state;
    s.detections = last_detections;
    s.scan = last_scan;
    s.camera_jpeg = last_image;
    s.lidar_pose = car->truth().body_pose3() * sim::lidar_mount(car_settings.lidar);
    // Ground truth on its own channels, so the stack's estimate above is never confused with it.
    s.truth = fsd::truth_state(*car);
    if (!truth_cones || car->cones_hit() != truth_cones_hit) {
      truth_cones = std::make_shared<const std::vector<web::TruthCone>>(fsd::truth_cones(car->world()));
      truth_cones_hit = car->cones_hit();
    }
    s.truth_cones = truth_cones;
    telemetry->publish(std::move(s));
  }

  // Copies the registry's values into the configuration and hands the control part to the autopilot; runs on the
  // loop's thread, so the autopilot is never touched from the web's.
  void apply_params() {
    AutopilotConfig ac = tuned_control(tuned, *params, run.laps);
    if (headless) ac.supervisor.check_plan_time = false;
    autopilot->set_config(ac);
  }

  int run_loop(const std::atomic<bool>& stop) {
    const auto wall0 = std::chrono::steady_clock::now();
    SimulatedClock pace(1.0);
    Stamp t = 0;
    double stopped_since = -1;
    int cycle = 0;
    log->info("driving {} on {} ({} lap(s)), seed {}, {}", to_string(mission), track.name,
              timed_laps(mission, run.laps), run.seed, headless ? "headless lockstep" : "real time");
    while (!stop.load(std::memory_order_relaxed)) {
      t = (++cycle) * kControlPeriod;
      if (!headless && !pace.sleep_until(t)) break;
      car->advance_to(t);
      faults->on_cycle(t, *autopilot);
      card->on_truth(car->truth());
      vcu->tick(t, [this, t](std::vector<std::uint8_t> bytes) { car->feed_vcu(t, bytes); });
      if (const auto st = vcu->status()) autopilot->on_vcu(*st);

      const sim::VehicleTruth& truth = car->truth();
      CycleFigures fig;  // for /metrics
      std::optional<std::chrono::steady_clock::time_point> frame_start;
      if (faults->perception_due(t, last_scan.get())) {
        const auto p0 = std::chrono::steady_clock::now();
        frame_start = p0;
        const std::vector<Cone> standing = car->standing_cones();
        auto det = perception.detect(t, standing, truth.pose);
        cone_map.update(det, truth.pose);
        autopilot->on_cones(t, cone_map.cones());
        fig.perception_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - p0).count();
        card->latency("perception").add(fig.perception_s);
        perception_score.add_frame(det, standing, truth.pose);  // the scorecard's, outside the stage's time
        last_detections = std::make_shared<const ConeDetections>(std::move(det));
      }
      autopilot->on_state(stack_state = state_from_truth(truth));
      if (params_changed.exchange(false)) apply_params();
      const ControlOutput out = autopilot->step(t);
      step_log.update(out, autopilot->faults());
      vcu->set_command(out.command, t);
      if (frame_start) {
        fig.end_to_end_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - *frame_start).count();
        card->latency("end_to_end").add(fig.end_to_end_s);
      }
      vcu->set_as_request(out.request);
      if (out.planned) card->latency("planning").add(out.planning_time);
      card->latency("control").add(out.control_time);

      const std::size_t laps_done = autopilot->lap_times().size();
      view->on_cycle(t, car->vcu().state(), out, laps_done, stack_state.pose.position(), static_cast<std::uint64_t>(cycle));
      card->set_as_state(car->vcu().state());
      card->set_cones_hit(car->cones_hit());
      if (cycle % 4 == 0) publish_telemetry(t, out);
      if (metrics) {
        fig.t = t;
        add_step_figures(fig, out);
        fig.as_state = car->vcu().state();
        fig.laps = static_cast<int>(laps_done);
        fig.cones_hit = car->cones_hit();
        metrics->on_cycle(fig);
      }

      // The end of a run: the mission is over and the car stands (Finished or Emergency), or time ran out.
      const AsState as = car->vcu().state();
      const bool resting = truth.speed() < 0.05;
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
    card->set_wall_time(std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count());
    for (const auto& f : link_faults) card->add_fault(f);
    for (const auto& f : autopilot->faults()) card->add_fault({f.t, f.source, f.what, f.action});
    card->set_section("injected_faults", faults->report());
    card->set_section("map", to_json(score_map(track.cones, cone_map.cones())));
    card->set_section("perception", perception_score.to_json());
    const auto vc = vcu->counters();
    log->info("run over at t = {:.2f} s: AS {}, {} lap(s), {} cone(s) hit, {} VCU commands, {} statuses", t,
              to_string(car->vcu().state()), card->laps_completed(), car->cones_hit(), vc.commands_sent,
              vc.statuses);
    if (!until_finished) return 0;
    return card->mission_succeeded() ? 0 : 1;
  }
};

SimRun::SimRun(const Config& config, const RunOptions& options) : impl_(std::make_unique<Impl>(config, options)) {}
SimRun::~SimRun() = default;
int SimRun::run(const std::atomic<bool>& stop) { return impl_->run_loop(stop); }
const Scorecard& SimRun::scorecard() const { return *impl_->card; }
void SimRun::set_telemetry(Telemetry* telemetry) { impl_->telemetry = telemetry; }
void SimRun::set_metrics(RunMetrics* metrics) { impl_->metrics = metrics; }
void SimRun::set_params(ParamRegistry* params) {
  impl_->params = params;
  if (params) params->subscribe([this](const ParamChange&) { impl_->params_changed = true; });
}

}  // namespace fsd
