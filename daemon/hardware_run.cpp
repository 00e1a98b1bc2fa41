#include "daemon/hardware_run.hpp"

#include <chrono>
#include <filesystem>
#include <mutex>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "common/bounded_queue.hpp"
#include "common/clock.hpp"
#include "common/logging.hpp"
#include "common/params.hpp"
#include "common/track.hpp"
#include "control/autopilot.hpp"
#include "control/control_config.hpp"
#include "daemon/cli.hpp"
#include "daemon/dashboard_view.hpp"
#include "daemon/gnss_state.hpp"
#include "daemon/hardware_stats.hpp"
#include "daemon/lap_build_thread.hpp"
#include "daemon/live_tuning.hpp"
#include "daemon/run_metrics.hpp"
#include "daemon/settings.hpp"
#include "daemon/step_log.hpp"
#include "daemon/telemetry.hpp"
#include "drivers/camera/camera_source.hpp"
#include "drivers/gnss/gnss_driver.hpp"
#include "drivers/serial/serial_port.hpp"
#include "drivers/vcu/vcu_link.hpp"
#include "drivers/vlp16/scan_builder.hpp"
#include "drivers/vlp16/udp_receiver.hpp"

namespace fsd {

namespace {

constexpr double kControlPeriod = 0.01;  // s: 100 Hz
constexpr int kTelemetryEvery = 4;       // control cycles between telemetry snapshots (25 Hz)
constexpr double kCameraJpegPeriod = 0.2;  // s between camera frames encoded for the dashboard

// A serial device must be there at start: a typo in the path should not look like a VCU that never answers.
// (Once running, a device that disappears is the drivers' business: they reopen it and report the gap.)
void require_serial_device(const std::string& key, const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (path.empty()) throw std::invalid_argument(key + " is empty: set it to the device's path");
  if (!fs::exists(path, ec)) throw std::invalid_argument(key + ": no such device '" + path + "'");
  if (!fs::is_character_file(path, ec))
    throw std::invalid_argument(key + ": '" + path + "' is not a character device (serial port)");
}

void require_camera_source(const CameraDriverConfig& c) {
  namespace fs = std::filesystem;
  std::error_code ec;
  switch (classify_camera_source(c.source)) {
    case CameraSourceKind::Pipeline: return;  // GStreamer checks it when it opens
    case CameraSourceKind::Device: {
      const bool index = c.source.rfind("/dev/", 0) != 0;
      const std::string path = index ? "/dev/video" + c.source : c.source;
      if (!fs::exists(path, ec)) throw std::invalid_argument("drivers.camera.source: no such device '" + path + "'");
      return;
    }
    case CameraSourceKind::File:
      if (!fs::is_regular_file(c.source, ec))
        throw std::invalid_argument("drivers.camera.source: no such video file '" + c.source + "'");
      return;
  }
}

struct GnssFix {
  GnssSample sample;
  bool have_origin = false;  // the driver has placed its local ENU origin
};

struct AsChange {
  Stamp t;
  AsState from, to;
};

}  // namespace

std::optional<std::string> hardware_mission_refusal(Mission m) {
  switch (m) {
    case Mission::Inspection: return std::nullopt;
    case Mission::EbsTest:
      return "mission 'ebs_test' needs perception (it drives a straight fitted to the cones and brakes at a "
             "distance along it): not available in this version; use --sim";
    default:
      return "mission '" + std::string(to_string(m)) + "' needs perception: not available in this version; use --sim";
  }
}

struct HardwareRun::Impl {
  RunSettings run;
  Mission mission = Mission::None;
  bool until_finished = false;
  RealClock clock;
  std::shared_ptr<spdlog::logger> log = logger("run");
  StepLog step_log{log};

  Vlp16Config vlp_cfg;
  GnssConfig gnss_cfg;
  VcuLinkConfig vcu_cfg;
  CameraDriverConfig cam_cfg;

  // LiDAR: decoded on the receiver's thread; the scans wait in a slot for perception (not wired yet).
  std::unique_ptr<Vlp16ScanBuilder> scans;
  std::unique_ptr<UdpReceiver> lidar_rx;
  std::unique_ptr<UdpReceiver> position_rx;   // VLP-16 position packets
  PositionPacketParser position_parser;        // guarded by lidar_m
  PpsState position_pps = PpsState::Absent;    // guarded by lidar_m
  LatestValue<std::shared_ptr<const Scan>> last_scan;
  mutable std::mutex lidar_m;
  LidarCounters lidar_counts;  // decode part, guarded by lidar_m

  // GNSS-INS: parsed on the serial port's thread.
  std::unique_ptr<GnssDriver> gnss;
  std::unique_ptr<SerialPort> gnss_port;
  LatestValue<GnssFix> gnss_slot;
  mutable std::mutex gnss_m;
  GnssCounters gnss_counts;  // guarded by gnss_m

  std::unique_ptr<VcuLink> vcu;

  std::unique_ptr<CameraSource> camera;
  std::thread camera_thread;
  LatestValue<std::shared_ptr<const Frame>> last_frame;

  std::unique_ptr<Autopilot> autopilot;
  std::thread control_thread;

  // The dashboard, when there is one (set before run()).
  Telemetry* telemetry = nullptr;
  RunMetrics* metrics = nullptr;
  ParamRegistry* params = nullptr;
  std::atomic<bool> params_changed{false};
  Config tuned;  // the configuration with the live parameter values (control thread)
  LatestValue<std::shared_ptr<const std::vector<std::uint8_t>>> camera_jpeg;  // encoded on the camera thread
  // Control thread only: what the snapshots show.
  std::optional<VehicleState> last_state;
  std::unique_ptr<DashboardView> view;
  std::atomic<bool> halt{false};          // the control and camera threads end
  std::atomic<bool> control_done{false};  // the control thread ended the run (--until-finished)
  std::atomic<std::uint64_t> cycles{0}, overruns{0};

  // Results. Written by the control thread (and the VCU link's threads for link faults), read after the joins.
  mutable std::mutex result_m;
  AsState as_state = AsState::Off;
  std::vector<AsChange> transitions;
  std::vector<nlohmann::json> link_faults;
  std::optional<Vec2> start_position;
  double max_distance_from_start = 0;
  std::string ended_by = "not started";
  double wall_time = 0;
  std::optional<HardwareCounters> final_counters;

  Impl(const Config& cfg, const RunOptions& opt)
      : run(run_section().read(cfg)),
        vlp_cfg(vlp16_section().read(cfg)),
        gnss_cfg(gnss_section().read(cfg)),
        vcu_cfg(vcu_section().read(cfg)),
        cam_cfg(camera_driver_section().read(cfg)),
        tuned(cfg) {
    until_finished = opt.until_finished;
    const auto m = mission_from_string(run.mission);
    if (!m) throw std::invalid_argument("unknown mission '" + run.mission + "'");
    mission = *m;
    if (const auto why = hardware_mission_refusal(mission)) throw std::invalid_argument(*why);
    require_serial_device("drivers.vcu.device", vcu_cfg.device);
    require_serial_device("drivers.gnss.device", gnss_cfg.device);
    if (cam_cfg.enabled) require_camera_source(cam_cfg);

    scans = std::make_unique<Vlp16ScanBuilder>(vlp_cfg, [this](Scan&& s) {
      last_scan.set(std::make_shared<const Scan>(std::move(s)));
      ++lidar_counts.scans;  // under lidar_m: on_scan runs inside on_data_packet below
    });
    try {
      lidar_rx = std::make_unique<UdpReceiver>(
          UdpReceiver::Options{vlp_cfg.address, static_cast<std::uint16_t>(vlp_cfg.data_port),
                               vlp_cfg.receive_buffer_bytes, "vlp16 data"},
          clock, [this](Stamp t, std::span<const std::uint8_t> payload) {
            std::lock_guard lock(lidar_m);
            scans->on_data_packet(t, payload);
            lidar_counts.decode = scans->decode_counters();
            lidar_counts.lost_packets = scans->lost_packets();
          });
      position_rx = std::make_unique<UdpReceiver>(
          UdpReceiver::Options{vlp_cfg.address, static_cast<std::uint16_t>(vlp_cfg.position_port),
                               1 << 16, "vlp16 position"},
          clock, [this](Stamp, std::span<const std::uint8_t> payload) {
            std::lock_guard lock(lidar_m);
            PositionPacket p;
            if (position_parser.parse(payload, p) == PositionStatus::Ok) position_pps = p.pps;
          });
    } catch (const std::runtime_error& e) {
      throw std::invalid_argument(std::string("drivers.vlp16: ") + e.what());
    }

    gnss = std::make_unique<GnssDriver>(gnss_cfg, [this](const GnssSample& s) {
      gnss_slot.set({s, gnss->origin().has_value()});
    });
    gnss_port = std::make_unique<SerialPort>(
        SerialPortConfig{.device = gnss_cfg.device, .baud = gnss_cfg.baud},
        SerialPort::Handlers{.on_bytes =
                                 [this](std::span<const std::uint8_t> b) {
                                   std::lock_guard lock(gnss_m);
                                   gnss->feed(b, clock.now());
                                   gnss_counts = gnss->counters();
                                 },
                             .on_open = {},
                             .on_lost = [this](Stamp t, const std::string& why) {
                               log->warn("GNSS-INS port lost at {:.2f} s: {}", t, why);
                             },
                             .on_gap = [this](const SerialGap& g) {
                               log->info("GNSS-INS port back after {:.2f} s ({})", g.duration(), g.reason);
                             }},
        &clock);

    VcuLink::Handlers vh;
    vh.on_event = [this](const VcuLinkEvent& e) {
      std::lock_guard lock(result_m);
      if (link_faults.size() < 256)
        link_faults.push_back({{"t", e.t}, {"source", "vcu"}, {"what", describe(e)}});
    };
    vcu = std::make_unique<VcuLink>(vcu_cfg, clock, std::move(vh));
    vcu->set_mission(mission);

    if (cam_cfg.enabled) camera = std::make_unique<CameraSource>(cam_cfg, clock);

    AutopilotConfig ac = read_control(cfg);
    ac.mission.laps = run.laps;
    autopilot = std::make_unique<Autopilot>(ac, mission, ColourConvention::named(run.colours));
    // The lap-2 build must not hold up the 100 Hz control thread.
    autopilot->set_lap_builder(lap_build_thread());
    view = std::make_unique<DashboardView>(mission, run.laps);
  }

  HardwareCounters snapshot() const {
    HardwareCounters c;
    c.t = clock.now();
    c.lidar.udp = lidar_rx->counters();
    {
      std::lock_guard lock(lidar_m);
      c.lidar.decode = lidar_counts.decode;
      c.lidar.scans = lidar_counts.scans;
      c.lidar.lost_packets = lidar_counts.lost_packets;
      c.lidar.position = position_parser.counters();
      c.lidar.pps = position_pps;
    }
    c.lidar.position_udp = position_rx->counters();
    {
      std::lock_guard lock(gnss_m);
      c.gnss.nmea = gnss_counts;
    }
    c.gnss.port = gnss_port->counters();
    c.vcu = vcu->counters();
    if (camera) c.camera = camera->stats();
    c.control_cycles = cycles.load();
    c.control_overruns = overruns.load();
    return c;
  }

  void note_as(AsState s, Stamp t) {
    std::lock_guard lock(result_m);
    if (s == as_state) return;
    transitions.push_back({t, as_state, s});
    log->info("AS {} -> {} at {:.2f} s", to_string(as_state), to_string(s), t);
    as_state = s;
  }

  void note_position(Vec2 p) {
    std::lock_guard lock(result_m);
    if (!start_position) start_position = p;
    max_distance_from_start = std::max(max_distance_from_start, (p - *start_position).norm());
  }

  // The dashboard's view of a control cycle: its figures to /metrics, every kTelemetryEvery-th a snapshot to the
  // telemetry (both hand over without waiting).
  void observe(Stamp now, AsState as, const ControlOutput& out, std::uint64_t cycle) {
    const std::size_t laps_done = autopilot->lap_times().size();
    std::optional<Vec2> position;
    if (last_state) position = last_state->pose.position();
    view->on_cycle(now, as, out, laps_done, position, cycle);
    if (metrics) {
      CycleFigures fig;
      fig.t = now;
      add_step_figures(fig, out);
      fig.as_state = as;
      fig.laps = static_cast<int>(laps_done);
      metrics->on_cycle(fig);
    }
    if (telemetry && cycle % kTelemetryEvery == 0) publish_telemetry(now, as, out);
  }

  void publish_telemetry(Stamp now, AsState as, const ControlOutput& out) {
    TelemetrySnapshot s = view->snapshot(now, as, out, *autopilot, vcu->status());
    if (last_state) {
      s.state = *last_state;
      // The newest scan, placed by the estimated pose and the configured mount (drivers.vlp16.mount_*).
      if (auto scan = last_scan.get()) {
        s.scan = std::move(*scan);
        s.lidar_pose = last_state->pose.to_pose3() * vlp_cfg.body_from_sensor();
      }
    }
    if (auto jpeg = camera_jpeg.get()) s.camera_jpeg = std::move(*jpeg);
    telemetry->publish(std::move(s));
  }

  // The control thread: newest inputs from the slots, one autopilot step, command and request to the VCU link's
  // slots. Never blocks on a driver.
  void control_loop() {
    std::uint64_t gnss_seen = 0;
    double steering = 0;
    Stamp next = clock.now();
    std::uint64_t cycle = 0;
    while (!halt.load()) {
      next += kControlPeriod;
      clock.sleep_until(next);
      const Stamp now = clock.now();
      if (now - next > kControlPeriod) {  // a whole period late: skip the missed cycles rather than burst
        overruns.fetch_add(1);
        next = now;
      }
      AsState as = AsState::Off;
      if (const auto st = vcu->status()) {
        steering = st->steering_measured;
        autopilot->on_vcu(*st);  // stamped with its arrival: a stale one trips the supervisor's watchdog
        as = st->as_state;
        note_as(as, now);
      }
      if (const auto fix = gnss_slot.get_if_newer(gnss_seen)) {
        autopilot->on_gnss(fix->sample.stamp, fix->sample.good);
        if (gnss_pose_usable(fix->sample, fix->have_origin)) {
          const VehicleState s = state_from_gnss(fix->sample, steering);
          autopilot->on_state(s);
          note_position(s.pose.position());
          last_state = s;
        }
      }
      if (params_changed.exchange(false)) autopilot->set_config(tuned_control(tuned, *params, run.laps));
      const ControlOutput out = autopilot->step(now);
      step_log.update(out, autopilot->faults());
      vcu->set_command(out.command);
      vcu->set_as_request(out.request);
      cycles.fetch_add(1);
      ++cycle;
      if (telemetry || metrics) observe(now, as, out, cycle);
      if (until_finished && (as == AsState::Finished || as == AsState::Emergency)) {
        std::lock_guard lock(result_m);
        ended_by = as == AsState::Finished ? "finished" : "emergency";
        control_done = true;
        return;
      }
    }
  }

  void camera_loop() {
    Stamp next_jpeg = 0;
    while (!halt.load())
      if (auto f = camera->next_frame(std::chrono::milliseconds(100))) {
        // The dashboard's picture is encoded here, on the camera's own thread, a few times a second.
        if (telemetry && f->stamp >= next_jpeg && !f->bgr.empty()) {
          std::vector<std::uint8_t> jpeg;
          if (cv::imencode(".jpg", f->bgr, jpeg, {cv::IMWRITE_JPEG_QUALITY, 80}))
            camera_jpeg.set(std::make_shared<const std::vector<std::uint8_t>>(std::move(jpeg)));
          next_jpeg = f->stamp + kCameraJpegPeriod;
        }
        last_frame.set(std::make_shared<const Frame>(std::move(*f)));
      }
  }

  int run_loop(const std::atomic<bool>& stop) {
    const auto wall0 = std::chrono::steady_clock::now();
    log->info("{} on the car: VLP-16 on udp {}:{} (position packets :{}), GNSS-INS on {} at {} baud, VCU on {} at {} baud, camera {}",
              to_string(mission), vlp_cfg.address, lidar_rx->port(), position_rx->port(), gnss_cfg.device, gnss_cfg.baud,
              vcu_cfg.device, vcu_cfg.baud, camera ? cam_cfg.source : std::string("off"));
    log->info("no perception in this version: state from GNSS-INS only, no cone detections");
    vcu->start();
    gnss_port->start();
    lidar_rx->start();
    position_rx->start();
    if (camera) {
      camera->start();
      camera_thread = std::thread([this] { camera_loop(); });
    }
    control_thread = std::thread([this] { control_loop(); });

    HardwareCounters prev = snapshot();
    Stamp next_stats = prev.t + run.stats_period;
    while (!stop.load() && !control_done.load()) {
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
      if (clock.now() >= next_stats) {
        const HardwareCounters now = snapshot();
        log->info("{}", rates_line(prev, now));
        prev = now;
        next_stats += run.stats_period;
      }
    }
    {
      std::lock_guard lock(result_m);
      if (!control_done.load()) ended_by = "signal";
    }
    log->info("stopping ({}): safe stop to the VCU first", ended_by);
    halt = true;
    control_thread.join();
    vcu->stop();  // sends drivers.vcu.stop_frames safe Commands, then closes the port
    if (camera) {
      camera->stop();
      camera_thread.join();
    }
    gnss_port->stop();
    lidar_rx->stop();
    position_rx->stop();
    final_counters = snapshot();
    log->info("totals: {}", rates_line(HardwareCounters{}, *final_counters));
    wall_time = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
    log->info("run over after {:.1f} s: AS {}, {} AS transition(s), {} fault(s)", wall_time, to_string(as_state),
              transitions.size(), autopilot->faults().size() + link_faults.size());
    if (!until_finished) return kExitOk;
    return as_state == AsState::Finished ? kExitOk : kExitMissionFailed;
  }

  nlohmann::json report() const {
    using nlohmann::json;
    std::lock_guard lock(result_m);
    json j;
    j["mode"] = "hardware";
    j["mission"] = std::string(to_string(mission));
    j["as_state"] = std::string(to_string(as_state));
    j["mission_succeeded"] = as_state == AsState::Finished;
    j["ended_by"] = ended_by;
    j["wall_time_s"] = wall_time;
    j["as_transitions"] = json::array();
    for (const auto& c : transitions)
      j["as_transitions"].push_back(
          {{"t", c.t}, {"from", std::string(to_string(c.from))}, {"to", std::string(to_string(c.to))}});
    j["max_distance_from_start_m"] = max_distance_from_start;
    j["drivers"] = final_counters ? counters_json(*final_counters) : json(nullptr);
    j["faults"] = json::array();
    for (const auto& f : link_faults) j["faults"].push_back(f);
    for (const auto& f : autopilot->faults())
      j["faults"].push_back({{"t", f.t}, {"source", f.source}, {"what", f.what}, {"action", f.action}});
    return j;
  }
};

HardwareRun::HardwareRun(const Config& config, const RunOptions& options)
    : impl_(std::make_unique<Impl>(config, options)) {}
HardwareRun::~HardwareRun() = default;
int HardwareRun::run(const std::atomic<bool>& stop) { return impl_->run_loop(stop); }
nlohmann::json HardwareRun::report() const { return impl_->report(); }
int HardwareRun::lidar_port() const { return impl_->lidar_rx->port(); }
void HardwareRun::set_telemetry(Telemetry* telemetry) { impl_->telemetry = telemetry; }
void HardwareRun::set_metrics(RunMetrics* metrics) { impl_->metrics = metrics; }
void HardwareRun::set_params(ParamRegistry* params) {
  impl_->params = params;
  if (params) params->subscribe([this](const ParamChange&) { impl_->params_changed = true; });
}

}  // namespace fsd
