#include "daemon/feeders/hardware_run.hpp"

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
#include "daemon/cli/cli.hpp"
#include "daemon/dds/ros_time.hpp"
#include "daemon/dds/run_dds.hpp"
#include "daemon/feeders/hardware_stats.hpp"
#include "daemon/recording/recorder.hpp"
#include "daemon/scoring/scorecard.hpp"
#include "daemon/stack/settings.hpp"
#include "daemon/stack/stack.hpp"
#include "daemon/telemetry/run_metrics.hpp"
#include "drivers/camera/camera_calibration.hpp"
#include "drivers/camera/camera_source.hpp"
#include "drivers/gnss/gnss_config.hpp"
#include "drivers/serial/serial_port.hpp"
#include "drivers/vcu/vcu_link.hpp"
#include "drivers/vlp16/config.hpp"
#include "drivers/vlp16/udp_receiver.hpp"

namespace fsd {

namespace {

constexpr double kControlPeriod = 0.01;    // s: 100 Hz
constexpr std::size_t kFrameQueue = 4096;  // raw frames between two control cycles (~10 at full rate)
constexpr int kCameraJpegQuality = 85;

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
    case CameraSourceKind::Pipeline:
      return;  // GStreamer checks it when it opens
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

// A raw frame that owns its bytes, on its way from a driver thread to the control thread.
struct QueuedFrame {
  RawChannel channel;
  Stamp t;
  std::vector<std::uint8_t> bytes;
};

struct AsChange {
  Stamp t;
  AsState from, to;
};

Mission mission_of(const RunSettings& run) {
  const auto m = mission_from_string(run.mission);
  if (!m) throw std::invalid_argument("unknown mission '" + run.mission + "'");
  return *m;
}

}  // namespace

struct HardwareRun::Impl {
  RunSettings run;
  DaemonSettings daemon;
  Mission mission;
  bool until_finished = false;
  RealClock clock;
  std::shared_ptr<spdlog::logger> log = logger("run");

  Vlp16Config vlp_cfg;
  GnssConfig gnss_cfg;
  VcuLinkConfig vcu_cfg;
  CameraDriverConfig cam_cfg;

  std::unique_ptr<Stack> stack;
  std::unique_ptr<Recorder> recorder;         // --record: taps the Stack on the control thread
  std::unique_ptr<LogForwarding> record_log;  // the log lines into the recording (detached before the recorder goes)
  // Every driver thread hands its raw frames to the control thread through this queue, in arrival order.
  BoundedQueue<QueuedFrame> frames{kFrameQueue};

  std::unique_ptr<UdpReceiver> lidar_rx;
  std::unique_ptr<UdpReceiver> position_rx;  // VLP-16 position packets
  std::unique_ptr<SerialPort> gnss_port;
  std::unique_ptr<VcuLink> vcu;
  std::unique_ptr<CameraSource> camera;
  std::thread camera_thread;
  std::thread control_thread;

  std::atomic<bool> halt{false};          // the control and camera threads end
  std::atomic<bool> control_done{false};  // the control thread ended the run (--until-finished)
  std::atomic<std::uint64_t> cycles{0}, overruns{0};
  std::function<void()> loop_hook;   // after each control cycle (the service's watchdog)
  RunMetrics* metrics = nullptr;     // the dashboard's /metrics (set before the control thread starts)
  std::unique_ptr<dds::RunDds> dds;  // dds.enabled or run.perception_source = dds

  // Results. Written by the control thread, read after the joins (and by snapshot() under result_m).
  mutable std::mutex result_m;
  AsState as_state = AsState::Off;
  std::vector<AsChange> transitions;
  std::optional<Vec2> start_position;
  double max_distance_from_start = 0;
  std::string ended_by = "not started";
  double wall_time = 0;
  std::optional<HardwareCounters> final_counters;

  Impl(const Config& cfg, const RunOptions& opt)
      : run(run_section().read(cfg)),
        daemon(daemon_section().read(cfg)),
        mission(mission_of(run)),
        until_finished(opt.until_finished),
        vlp_cfg(read_vlp16_config(cfg)),
        gnss_cfg(read_gnss_config(cfg)),
        vcu_cfg(vcu_section().read(cfg)),
        cam_cfg(camera_driver_section().read(cfg)) {
    require_serial_device("drivers.vcu.device", vcu_cfg.device);
    require_serial_device("drivers.gnss.device", gnss_cfg.device);
    if (cam_cfg.enabled) require_camera_source(cam_cfg);

    StackOptions so;
    so.mission = mission;
    so.laps = run.laps;
    so.lap_build_worker = true;     // the lap-2 build must not hold up the 100 Hz control thread
    so.plan_worker = true;          // nor lap 1's real-time plans
    so.loop_closure_worker = true;  // nor the loop closure's solve
    // The scans' processing stays inside the step on the car for now: a car run's recording must replay bit for bit
    // (HardwareRun.InspectionAgainstFsdSim...), and which cycle took each scan's result on the processing thread is
    // not recorded yet. The virtual car in real time runs it on the processing thread.
    so.scan_worker = false;
    so.worker_priority = worker_priority(daemon);
    so.start = clock.now();
    // The camera stage sees through the calibrated camera; its frames are stamped at capture already.
    if (!cam_cfg.calibration.empty())
      so.camera = StackOptions::Camera{load_camera_calibration(cam_cfg.calibration), 0.0};
    if (run.perception_source == "lidar_camera" && !cam_cfg.enabled)
      log->warn("run.perception_source = lidar_camera with drivers.camera.enabled = false: LiDAR-only detections");
    stack = std::make_unique<Stack>(cfg, so);
    if (!opt.record.empty()) {
      RecordingContents rc;
      rc.config = &cfg.as_json();
      rc.run = {"car", false, so.mission, so.laps, so.simulator, so.start, std::nullopt, ""};
      rc.car = web::car_shape_of(read_car(cfg));
      if (so.camera) {
        rc.run.camera_latency = so.camera->latency;
        rc.run.camera_calibration = to_json(so.camera->calibration).dump();
      }
      recorder = std::make_unique<Recorder>(opt.record, record_section().read(cfg), rc);
      stack->add_tap(recorder.get());
      record_log = std::make_unique<LogForwarding>(recorder->log_sink());  // before any thread of the run logs
    }

    auto to_stack = [this](RawChannel c) {
      return [this, c](Stamp t, std::span<const std::uint8_t> b) {
        frames.push({c, t, std::vector<std::uint8_t>(b.begin(), b.end())});
      };
    };
    try {
      lidar_rx = std::make_unique<UdpReceiver>(
          UdpReceiver::Options{vlp_cfg.address, static_cast<std::uint16_t>(vlp_cfg.data_port),
                               vlp_cfg.receive_buffer_bytes, "vlp16 data"},
          clock, to_stack(RawChannel::Vlp16Data));
      position_rx = std::make_unique<UdpReceiver>(
          UdpReceiver::Options{vlp_cfg.address, static_cast<std::uint16_t>(vlp_cfg.position_port), 1 << 16,
                               "vlp16 position"},
          clock, to_stack(RawChannel::Vlp16Position));
    } catch (const std::runtime_error& e) {
      throw std::invalid_argument(std::string("drivers.vlp16: ") + e.what());
    }

    gnss_port = std::make_unique<SerialPort>(
        SerialPortConfig{.device = gnss_cfg.device, .baud = gnss_cfg.baud},
        SerialPort::Handlers{
            .on_bytes = [this,
                         feed = to_stack(RawChannel::Nmea)](std::span<const std::uint8_t> b) { feed(clock.now(), b); },
            .on_open = {},
            .on_lost = [this](Stamp t,
                              const std::string& why) { log->warn("GNSS-INS port lost at {:.2f} s: {}", t, why); },
            .on_gap =
                [this](const SerialGap& g) {
                  log->info("GNSS-INS port back after {:.2f} s ({})", g.duration(), g.reason);
                }},
        &clock);

    VcuLink::Handlers vh;
    vh.on_event = [this](const VcuLinkEvent& e) { stack->report_link_event(e); };
    vh.on_rx_bytes = to_stack(RawChannel::VcuRx);
    vh.on_tx_bytes = to_stack(RawChannel::VcuTx);
    vcu = std::make_unique<VcuLink>(vcu_cfg, stack->vcu(), clock, std::move(vh));

    if (cam_cfg.enabled) camera = std::make_unique<CameraSource>(cam_cfg, clock);
    dds = dds::RunDds::make(cfg, false);
    if (dds) dds->start(*stack, dds::run_epoch(clock.now()));
  }

  HardwareCounters snapshot() const {
    HardwareCounters c;
    c.t = clock.now();
    const StackCounters s = stack->counters();
    c.lidar.udp = lidar_rx->counters();
    c.lidar.decode = s.lidar;
    c.lidar.scans = s.scans;
    c.lidar.lost_packets = s.lidar_lost_packets;
    c.lidar.position = s.position;
    c.lidar.pps = s.pps;
    c.lidar.position_udp = position_rx->counters();
    c.gnss.nmea = s.gnss;
    c.gnss.port = gnss_port->counters();
    c.vcu = {s.vcu, vcu->counters().port};
    if (camera) c.camera = camera->stats();
    c.control_cycles = cycles.load();
    c.control_overruns = overruns.load();
    c.frames_dropped = frames.dropped();
    return c;
  }

  void note_cycle(Stamp now) {
    std::lock_guard lock(result_m);
    const AsState s = stack->as_state();
    if (s != as_state) {
      transitions.push_back({now, as_state, s});
      log->info("AS {} -> {} at {:.2f} s", to_string(as_state), to_string(s), now);
      as_state = s;
    }
    if (const auto& st = stack->state()) {
      const Vec2 p = st->pose.position();
      if (!start_position) start_position = p;
      max_distance_from_start = std::max(max_distance_from_start, (p - *start_position).norm());
    }
  }

  // The control thread: the frames that arrived since the last cycle into the Stack, in order, then one cycle.
  // Never blocks on a driver.
  void control_loop() {
    make_control_thread_realtime(daemon);
    Stamp next = clock.now();
    while (!halt.load()) {
      next += kControlPeriod;
      clock.sleep_until(next);
      if (metrics) metrics->on_cycle_start();
      const Stamp now = clock.now();
      if (now - next > kControlPeriod) {  // a whole period late: skip the missed cycles rather than burst
        overruns.fetch_add(1);
        next = now;
      }
      while (auto f = frames.try_pop()) stack->feed({f->channel, f->t, f->bytes});
      if (dds) dds->before_step(*stack);
      stack->step(now);
      cycles.fetch_add(1);
      if (loop_hook) loop_hook();
      note_cycle(now);
      const AsState as = stack->as_state();
      if (until_finished && (as == AsState::Finished || as == AsState::Emergency)) {
        std::lock_guard lock(result_m);
        ended_by = as == AsState::Finished ? "finished" : "emergency";
        control_done = true;
        return;
      }
    }
  }

  // The camera's frames go to the Stack as an MJPEG camera sends them: JPEG, encoded here on the camera's thread.
  void camera_loop() {
    while (!halt.load())
      if (auto f = camera->next_frame(std::chrono::milliseconds(100))) {
        if (f->bgr.empty()) continue;
        std::vector<std::uint8_t> jpeg;
        if (cv::imencode(".jpg", f->bgr, jpeg, {cv::IMWRITE_JPEG_QUALITY, kCameraJpegQuality}))
          frames.push({RawChannel::Camera, f->stamp, std::move(jpeg)});
      }
  }

  int run_loop(const std::atomic<bool>& stop) {
    const auto wall0 = std::chrono::steady_clock::now();
    log->info(
        "{} on the car: VLP-16 on udp {}:{} (position packets :{}), GNSS-INS on {} at {} baud, VCU on {} at {} baud, "
        "camera {}",
        to_string(mission), vlp_cfg.address, lidar_rx->port(), position_rx->port(), gnss_cfg.device, gnss_cfg.baud,
        vcu_cfg.device, vcu_cfg.baud, camera ? cam_cfg.source : std::string("off"));
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
    if (dds) {
      dds->stop();
      log->info("{}", dds->summary());
    }
    vcu->stop();  // sends drivers.vcu.stop_frames safe Commands, then closes the port
    if (camera) {
      camera->stop();
      camera_thread.join();
    }
    gnss_port->stop();
    lidar_rx->stop();
    position_rx->stop();
    // What arrived after the last cycle is still decoded (and recorded): every datagram received is counted.
    while (auto f = frames.try_pop()) stack->feed({f->channel, f->t, f->bytes});
    if (recorder) recorder->close();
    final_counters = snapshot();
    log->info("totals: {}", rates_line(HardwareCounters{}, *final_counters));
    wall_time = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
    log->info("run over after {:.1f} s: AS {}, {} AS transition(s), {} fault(s)", wall_time, to_string(as_state),
              transitions.size(), stack->faults().size());
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
    j["latency_ms"] = latency_json(stack->latencies());
    j["faults"] = faults_json(stack->faults());
    if (recorder) j["recording"] = to_json(recorder->stats());
    return j;
  }
};

HardwareRun::HardwareRun(const Config& config, const RunOptions& options)
    : impl_(std::make_unique<Impl>(config, options)) {}
HardwareRun::~HardwareRun() = default;
int HardwareRun::run(const std::atomic<bool>& stop) { return impl_->run_loop(stop); }
nlohmann::json HardwareRun::report() const { return impl_->report(); }
int HardwareRun::lidar_port() const { return impl_->lidar_rx->port(); }
void HardwareRun::set_telemetry(Telemetry* telemetry) { impl_->stack->set_telemetry(telemetry); }
void HardwareRun::set_metrics(RunMetrics* metrics) {
  impl_->metrics = metrics;
  impl_->stack->set_metrics(metrics);
  if (metrics && impl_->recorder) impl_->recorder->set_metrics(metrics->registry());
}
void HardwareRun::set_params(ParamRegistry* params) { impl_->stack->set_params(params); }
void HardwareRun::set_loop_hook(std::function<void()> hook) { impl_->loop_hook = std::move(hook); }

const Stack& HardwareRun::stack() const { return *impl_->stack; }

}  // namespace fsd
