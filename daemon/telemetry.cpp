#include "daemon/telemetry.hpp"

#include <chrono>

#include "web/server.hpp"

namespace fsd {

Telemetry::Telemetry(web::WebServer& server, TelemetryRates rates)
    : server_(server), ch_(web::add_standard_channels(server)), rates_(rates), thread_([this] { loop(); }) {}

Telemetry::~Telemetry() { stop(); }

void Telemetry::stop() {
  stop_ = true;
  if (thread_.joinable()) thread_.join();
}

void Telemetry::publish(TelemetrySnapshot snapshot) {
  latest_.set(std::make_shared<const TelemetrySnapshot>(std::move(snapshot)));
}

void Telemetry::loop() {
  using clock = std::chrono::steady_clock;
  // Each channel is due when its period has passed in wall time: the dashboard wants smooth real-time updates,
  // also while a headless-fast run races through simulated time.
  struct Due {
    double period;
    clock::time_point next;
  };
  auto due = [](double hz) { return Due{1.0 / hz, clock::now()}; };
  Due state = due(rates_.state_hz), car = due(rates_.car_hz), scene = due(rates_.scene_hz),
      cloud = due(rates_.cloud_hz), status = due(rates_.status_hz), camera = due(rates_.camera_hz);
  auto ready = [](Due& d, clock::time_point now) {
    if (now < d.next) return false;
    d.next = now + std::chrono::duration_cast<clock::duration>(std::chrono::duration<double>(d.period));
    return true;
  };
  std::uint64_t seen = 0;
  std::shared_ptr<const Scan> last_scan;
  std::shared_ptr<const std::vector<std::uint8_t>> last_image;
  while (!stop_) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
    const auto snap_opt = latest_.get_if_newer(seen);
    if (!snap_opt) continue;
    const TelemetrySnapshot& s = **snap_opt;
    const auto now = clock::now();
    if (ready(state, now)) server_.publish(ch_.vehicle_state, s.t, web::vehicle_state_json(s.state, s.target_speed));
    if (ready(car, now)) server_.publish(ch_.car, s.t, web::car_scene(s.t, s.state.pose));
    if (ready(scene, now)) {
      if (s.cone_map) server_.publish(ch_.cone_map, s.t, web::cone_map_scene(s.t, *s.cone_map));
      if (s.detections) server_.publish(ch_.detections, s.t, web::detections_scene(s.t, *s.detections, s.state.pose));
      if (s.paths) server_.publish(ch_.paths, s.t, web::paths_scene(s.t, *s.paths));
    }
    if (s.scan && s.scan != last_scan && ready(cloud, now)) {
      last_scan = s.scan;
      server_.publish(ch_.point_cloud, s.t, web::point_cloud(s.t, s.lidar_pose, {}, s.scan->points));
    }
    if (s.camera_jpeg && s.camera_jpeg != last_image && ready(camera, now)) {
      last_image = s.camera_jpeg;
      server_.publish(ch_.camera_image, s.t, web::compressed_image(s.t, *s.camera_jpeg, "jpeg"));
    }
    if (ready(status, now)) {
      server_.publish(ch_.as_status, s.t, web::as_status_json(s.t, s.as));
      server_.publish(ch_.faults, s.t, web::faults_json(s.t, s.faults));
    }
  }
}

}  // namespace fsd
