#include "daemon/telemetry.hpp"

#include <algorithm>
#include <chrono>

#include <spdlog/spdlog.h>
#include <nlohmann/json.hpp>

#include "web/log_sink.hpp"
#include "web/server.hpp"

namespace fsd {

namespace {

// /api/state: the newest snapshot in short (the channels carry the rest).
nlohmann::json state_json(const TelemetrySnapshot& s) {
  const auto& v = s.state;
  nlohmann::json j = {
      {"t", s.t},
      {"as_state", std::string(to_string(s.as.as_state))},
      {"mission", std::string(to_string(s.as.mission))},
      {"lap", s.as.lap},
      {"laps_completed", s.as.laps_completed},
      {"laps_total", s.as.laps_total},
      {"lap_times", s.as.lap_times},
      {"control_mode", s.as.control_mode},
      {"finished", s.as.finished},
      {"vehicle",
       {{"x", v.pose.x},
        {"y", v.pose.y},
        {"yaw", v.pose.yaw},
        {"speed", v.speed()},
        {"yaw_rate", v.yaw_rate},
        {"target_speed", s.target_speed}}},
      {"faults", static_cast<int>(s.faults.size())},
  };
  if (s.truth) j["truth"] = {{"speed", s.truth->speed}, {"cones_hit", s.truth->cones_hit}};
  return j;
}

}  // namespace

Telemetry::Telemetry(web::WebServer& server, TelemetryRates rates, bool truth, web::CarShape car)
    : server_(server),
      ch_(web::add_standard_channels(server)),
      truth_ch_(truth ? std::optional(web::add_truth_channels(server)) : std::nullopt),
      rates_(rates),
      car_(car),
      published_(
          server.metrics().counter("fsd_telemetry_snapshots_total", "Snapshots the control loop handed to telemetry")),
      skipped_(server.metrics().counter("fsd_telemetry_snapshots_skipped_total",
                                        "Snapshots replaced by a newer one before the telemetry thread took them")),
      thread_([this] { loop(); }) {
  server_.set_state_provider([slot = latest_]() -> nlohmann::json {
    const auto snap = slot->get();
    if (!snap || !*snap) return {{"t", nullptr}, {"as_state", nullptr}};
    return state_json(**snap);
  });
}

Telemetry::~Telemetry() { stop(); }

void Telemetry::stop() {
  stop_ = true;
  if (thread_.joinable()) thread_.join();
}

void Telemetry::publish(std::shared_ptr<const TelemetrySnapshot> snapshot) {
  latest_->set(std::move(snapshot));
  published_.inc();
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
      cloud = due(rates_.cloud_hz), status = due(rates_.status_hz), camera = due(rates_.camera_hz),
      truth_state = due(rates_.state_hz), truth_cones = due(rates_.scene_hz);
  auto ready = [](Due& d, clock::time_point now) {
    if (now < d.next) return false;
    d.next = now + std::chrono::duration_cast<clock::duration>(std::chrono::duration<double>(d.period));
    return true;
  };
  std::uint64_t seen = 0;
  std::shared_ptr<const Scan> last_scan;
  std::shared_ptr<const LabelledCloud> last_cloud;
  std::shared_ptr<const std::vector<std::uint8_t>> last_image;
  std::shared_ptr<const std::vector<web::TruthCone>> last_truth_cones;
  std::shared_ptr<const TelemetrySnapshot> snap;
  while (!stop_) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
    const std::uint64_t before = seen;
    if (const auto newer = latest_->get_if_newer(seen)) {
      if (seen > before + 1) skipped_.inc(seen - before - 1);
      snap = *newer;
    } else if (!snap || !truth_ch_ || snap->truth_cones == last_truth_cones) {
      continue;  // nothing new (a pending truth cone update is retried below)
    }
    const TelemetrySnapshot& s = *snap;
    const auto now = clock::now();
    const bool fresh = seen != before;
    if (fresh && ready(state, now))
      server_.publish(ch_.vehicle_state, s.t, web::vehicle_state_json(s.state, s.target_speed));
    if (fresh && ready(car, now)) server_.publish(ch_.car, s.t, web::car_scene(s.t, s.state.pose, car_));
    if (fresh && ready(scene, now)) {
      if (s.cone_map) server_.publish(ch_.cone_map, s.t, web::cone_map_scene(s.t, *s.cone_map));
      // Drawn where they were seen: at the pose of their own instant (up to 100 ms before the snapshot's).
      if (s.detections)
        server_.publish(ch_.detections, s.t,
                        web::detections_scene(s.t, *s.detections, s.detections_pose.value_or(s.state.pose)));
      if (s.paths) server_.publish(ch_.paths, s.t, web::paths_scene(s.t, *s.paths));
    }
    if (fresh && s.cloud && s.cloud != last_cloud && ready(cloud, now)) {
      // Perception ran: the ground and the obstacles apart, as the detector split them.
      last_cloud = s.cloud;
      server_.publish(ch_.point_cloud, s.t, web::point_cloud(s.t, s.cloud_pose, s.cloud->ground, s.cloud->obstacles));
    } else if (fresh && !s.cloud && s.scan && s.scan != last_scan && ready(cloud, now)) {
      last_scan = s.scan;
      server_.publish(ch_.point_cloud, s.t, web::point_cloud(s.t, s.lidar_pose, {}, s.scan->points));
    }
    if (fresh && s.camera_jpeg && s.camera_jpeg != last_image && ready(camera, now)) {
      last_image = s.camera_jpeg;
      server_.publish(ch_.camera_image, s.t, web::compressed_image(s.t, *s.camera_jpeg, "jpeg"));
    }
    if (fresh && ready(status, now)) {
      server_.publish(ch_.as_status, s.t, web::as_status_json(s.t, s.as));
      server_.publish(ch_.faults, s.t, web::faults_json(s.t, s.faults));
    }
    if (truth_ch_) {
      if (fresh && s.truth && ready(truth_state, now)) {
        server_.publish(truth_ch_->vehicle_state, s.t, web::truth_state_json(*s.truth));
        server_.publish(truth_ch_->car, s.t, web::truth_car_scene(s.t, s.truth->pose, car_));
      }
      // The cones change only when one falls: sent then (latched for late subscribers), at most at the scene rate.
      if (s.truth_cones && s.truth_cones != last_truth_cones && ready(truth_cones, now)) {
        last_truth_cones = s.truth_cones;
        server_.publish(truth_ch_->cones, s.t, web::truth_cones_scene(s.t, *s.truth_cones));
      }
    }
  }
}

LogForwarding::LogForwarding(web::WebServer& server, web::ChannelId log_channel, const Clock& clock,
                             spdlog::level::level_enum level)
    : LogForwarding(web::make_log_sink(server, log_channel, clock, level)) {}

LogForwarding::LogForwarding(std::shared_ptr<spdlog::sinks::sink> sink) : sink_(std::move(sink)) {
  // The default logger's sinks are what fsd::logger() copies into loggers it creates later.
  auto attach = [this](const std::shared_ptr<spdlog::logger>& l) {
    auto& sinks = l->sinks();
    if (std::find(sinks.begin(), sinks.end(), sink_) == sinks.end()) sinks.push_back(sink_);
  };
  attach(spdlog::default_logger());
  spdlog::apply_all(attach);
}

LogForwarding::~LogForwarding() { detach(); }

void LogForwarding::detach() {
  if (!sink_) return;
  auto remove = [this](const std::shared_ptr<spdlog::logger>& l) {
    auto& sinks = l->sinks();
    sinks.erase(std::remove(sinks.begin(), sinks.end(), sink_), sinks.end());
  };
  remove(spdlog::default_logger());
  spdlog::apply_all(remove);
  sink_.reset();
}

}  // namespace fsd
