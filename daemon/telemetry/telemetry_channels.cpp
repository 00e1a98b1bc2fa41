#include "daemon/telemetry/telemetry_channels.hpp"

namespace fsd {

namespace {

namespace topics = web::topics;
using web::Schema;
using Built = std::optional<ChannelPayload>;

Built text(std::string json) { return ChannelPayload{std::move(json), std::nullopt}; }
Built scene(std::vector<nlohmann::json> entities) { return ChannelPayload{{}, std::move(entities)}; }

// Log lines a new subscriber gets at once: what happened before the page was opened (the dashboard shows 60).
constexpr std::size_t kLogBacklog = 100;

web::ChannelOptions latched() { return {.latched = true}; }
web::ChannelOptions latched_delta() { return {.latched = true, .delta = true}; }

std::vector<TelemetryChannel> make_table() {
  std::vector<TelemetryChannel> t;
  // Scene, sent as changes by entity (the dashboard's largest messages once sent whole 4 times a second).
  t.push_back(
      {.spec = web::channel_spec(topics::kConeMap, Schema::SceneUpdate, "Cone map in the map frame", latched_delta()),
       .live_hz = 2,  // a refined cone is sent again: twice a second is enough to watch the map grow
       .record_hz = 1,
       .source = [](const TelemetrySnapshot& s) -> std::shared_ptr<const void> { return s.cone_map; },
       .build = [](const TelemetrySnapshot& s,
                   const ChannelUse&) { return scene(web::cone_map_entities(s.t, *s.cone_map)); }});
  t.push_back(
      {.spec = web::channel_spec(topics::kDetections, Schema::SceneUpdate, "Cone detections of the latest LiDAR frame"),
       .live_hz = 4,  // each lives 0.5 s
       .record_hz = 4,
       .source = [](const TelemetrySnapshot& s) -> std::shared_ptr<const void> { return s.detections; },
       .build =
           [](const TelemetrySnapshot& s, const ChannelUse&) {
             // Drawn where they were seen: at the pose of their own instant (up to 100 ms before the snapshot's).
             return text(web::detections_scene(s.t, *s.detections, s.detections_pose.value_or(s.state.pose)));
           }});
  t.push_back({.spec = web::channel_spec(topics::kCar, Schema::SceneUpdate, "The car"),
               .live_hz = 25,
               .record_hz = 25,
               .build = [](const TelemetrySnapshot& s, const ChannelUse& u) {
                 return text(web::car_scene(s.t, s.state.pose, u.car));
               }});
  t.push_back({.spec = web::channel_spec(topics::kPaths, Schema::SceneUpdate,
                                         "Lap-1 trajectory, lap-2 tracking and the planned path", latched_delta()),
               .live_hz = 4,
               .record_hz = 1,
               .source = [](const TelemetrySnapshot& s) -> std::shared_ptr<const void> { return s.paths; },
               .build = [](const TelemetrySnapshot& s,
                           const ChannelUse&) { return scene(web::paths_entities(s.t, *s.paths)); }});
  // Perception's split of the newest scan when it ran, else the raw scan (the recording: only the split, thinned;
  // the raw VLP-16 packets hold every point).
  t.push_back(
      {.spec = web::channel_spec(topics::kPointCloud, Schema::PointCloud, "LiDAR points, downsampled, ground flagged"),
       .live_hz = 2,
       .record_hz = 1,
       .source = [](const TelemetrySnapshot& s) -> std::shared_ptr<const void> {
         if (s.cloud) return s.cloud;
         return s.scan;
       },
       .build = [](const TelemetrySnapshot& s, const ChannelUse& u) -> Built {
         web::CloudOptions o;
         o.max_points = u.recording ? 2000 : 4000;  // ~45 kB of JSON; live ~85 kB, 2 Hz within the Wi-Fi budget
         if (s.cloud) return text(web::point_cloud(s.t, s.cloud_pose, s.cloud->ground, s.cloud->obstacles, o));
         if (u.recording || !s.scan) return std::nullopt;
         return text(web::point_cloud(s.t, s.lidar_pose, {}, s.scan->points, o));
       }});
  // Not recorded: the raw JPEG frames are.
  t.push_back({.spec = web::channel_spec(topics::kCameraImage, Schema::CompressedImage, "Camera image"),
               .live_hz = 5,
               .source = [](const TelemetrySnapshot& s) -> std::shared_ptr<const void> { return s.camera_jpeg; },
               .build = [](const TelemetrySnapshot& s,
                           const ChannelUse&) { return text(web::compressed_image(s.t, *s.camera_jpeg, "jpeg")); }});
  t.push_back(
      {.spec = web::channel_spec(topics::kVehicleState, Schema::VehicleState, "Motion state of the car (SI units)"),
       .live_hz = 25,
       .record_hz = 25,
       .build = [](const TelemetrySnapshot& s, const ChannelUse&) {
         return text(web::vehicle_state_json(s.state, s.target_speed));
       }});
  t.push_back(
      {.spec =
           web::channel_spec(topics::kAsStatus, Schema::AsStatus, "Autonomous-system state, mission, laps", latched()),
       .live_hz = 5,
       .record_hz = 5,
       .changed = [](const TelemetrySnapshot& s) { return std::string(to_string(s.as.as_state)); },
       .build = [](const TelemetrySnapshot& s, const ChannelUse&) { return text(web::as_status_json(s.t, s.as)); }});
  t.push_back(
      {.spec = web::channel_spec(topics::kFaults, Schema::Faults, "Recent faults", latched()),
       .live_hz = 1,
       .record_hz = 0,  // recorded when the list changes
       .changed =
           [](const TelemetrySnapshot& s) {
             if (s.faults.empty()) return std::string();
             return std::to_string(s.faults.size()) + s.faults.back().source + s.faults.back().what;
           },
       .build = [](const TelemetrySnapshot& s, const ChannelUse&) { return text(web::faults_json(s.t, s.faults)); }});
  // The localization's view of itself: on the car as in the simulator (not recorded: a replay recomputes it).
  t.push_back({.spec = web::channel_spec(topics::kLocalization, Schema::Localization,
                                         "Localization source, quality and the filter's covariance"),
               .live_hz = 10,
               .build = [](const TelemetrySnapshot& s, const ChannelUse&) -> Built {
                 if (!s.localization) return std::nullopt;
                 return text(web::localization_json(*s.localization));
               }});
  t.push_back({.spec = web::channel_spec(topics::kLoopClosures, Schema::LoopClosures,
                                         "Every loop closure of the run: when, where, the correction", latched()),
               .live_hz = 1,
               .changed = [](const TelemetrySnapshot& s) { return std::to_string(s.loop_closures.size()); },
               .build = [](const TelemetrySnapshot& s, const ChannelUse&) {
                 return text(web::loop_closures_json(s.t, s.loop_closures));
               }});
  // Fed by the log sink (web::make_log_sink; the recorder's own), not from snapshots.
  t.push_back(
      {.spec = web::channel_spec(topics::kLog, Schema::Log, "Log lines (the latest 100 sent to a new subscriber)",
                                 {.backlog = kLogBacklog}),
       .live_hz = 0,
       .record_hz = 0});
  // Sim runs: the simulator's ground truth, apart from the stack's own estimates above.
  t.push_back({.spec = web::channel_spec(topics::kTruthCones, Schema::SceneUpdate,
                                         "Simulator ground truth: every cone, standing or knocked over", latched()),
               .truth = true,
               .live_hz = 4,  // the cones change only when one falls
               .source = [](const TelemetrySnapshot& s) -> std::shared_ptr<const void> { return s.truth_cones; },
               .build = [](const TelemetrySnapshot& s,
                           const ChannelUse&) { return text(web::truth_cones_scene(s.t, *s.truth_cones)); }});
  t.push_back(
      {.spec = web::channel_spec(topics::kTruthCar, Schema::SceneUpdate, "Simulator ground truth: the car's true pose"),
       .truth = true,
       .live_hz = 25,
       .build = [](const TelemetrySnapshot& s, const ChannelUse& u) -> Built {
         if (!s.truth) return std::nullopt;
         return text(web::truth_car_scene(s.t, s.truth->pose, u.car));
       }});
  t.push_back({.spec = web::channel_spec(topics::kTruthVehicleState, Schema::TruthVehicleState,
                                         "Simulator ground truth: the car's true motion (SI units)"),
               .truth = true,
               .live_hz = 25,
               .build = [](const TelemetrySnapshot& s, const ChannelUse&) -> Built {
                 if (!s.truth) return std::nullopt;
                 return text(web::truth_state_json(*s.truth));
               }});
  t.push_back({.spec = web::channel_spec(topics::kTruthPath, Schema::SceneUpdate,
                                         "Simulator ground truth: the path the car really drove", latched_delta()),
               .truth = true,
               .live_hz = 4,
               .source = [](const TelemetrySnapshot& s) -> std::shared_ptr<const void> { return s.truth_path; },
               .build = [](const TelemetrySnapshot& s,
                           const ChannelUse&) { return scene(web::truth_path_entities(s.t, *s.truth_path)); }});
  t.push_back({.spec = web::channel_spec(topics::kTruthLocalizationError, Schema::LocalizationError,
                                         "Simulator ground truth: the localization's position and heading error"),
               .truth = true,
               .live_hz = 10,
               .build = [](const TelemetrySnapshot& s, const ChannelUse&) -> Built {
                 if (!s.truth || !s.localization) return std::nullopt;
                 return text(web::localization_error_json(web::localization_error(s.state, *s.truth)));
               }});
  return t;
}

}  // namespace

const std::vector<TelemetryChannel>& telemetry_channels() {
  static const std::vector<TelemetryChannel> table = make_table();
  return table;
}

std::vector<web::ChannelSpec> channel_specs(const std::function<bool(const TelemetryChannel&)>& keep) {
  std::vector<web::ChannelSpec> out;
  for (const auto& row : telemetry_channels())
    if (keep(row)) out.push_back(row.spec);
  return out;
}

ChannelPacer::ChannelPacer(const std::vector<TelemetryChannel>& rows,
                           std::function<std::optional<double>(const TelemetryChannel&)> rate,
                           std::function<bool(const TelemetryChannel&)> use)
    : rows_(rows), state_(rows.size()) {
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const auto hz = rate(rows[i]);
    state_[i].active = rows[i].build && hz && (!use || use(rows[i]));
    state_[i].period = hz && *hz > 0 ? 1.0 / *hz : 0.0;
    state_[i].next = -1e300;
  }
}

std::vector<std::size_t> ChannelPacer::due(const TelemetrySnapshot& s, double now, bool fresh) {
  // Keeps the phase (next += period), so polling in steps does not stretch the period: a 25 Hz channel checked
  // every 10 ms gets 25 messages a second, not 20. After a pause it restarts from now rather than catching up.
  const auto by_rate = [now](Row& r) {
    if (r.period <= 0 || now + 1e-9 < r.next) return false;
    r.next += r.period;
    if (r.next <= now) r.next = now + r.period;
    return true;
  };
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < rows_.size(); ++i) {
    Row& r = state_[i];
    const TelemetryChannel& row = rows_[i];
    if (!r.active) continue;
    if (row.source) {
      auto src = row.source(s);
      if (!src || src == r.last_source || !by_rate(r)) continue;
      r.last_source = std::move(src);  // held, so a new pointer at a freed one's address is not taken for it
      out.push_back(i);
      continue;
    }
    if (!fresh) continue;
    bool now_changed = false;
    if (row.changed) {
      auto key = row.changed(s);
      now_changed = key != r.last_key;
      r.last_key = std::move(key);
    }
    if (by_rate(r) || now_changed) out.push_back(i);
  }
  return out;
}

}  // namespace fsd
