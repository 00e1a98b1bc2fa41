#pragma once
// The telemetry channels of the dashboard and of Foxglove Studio: topic names, JSON schemas, and builders that turn
// common/ types into the JSON payloads. Which channel has which schema, rate and builder is declared once, in the
// daemon's channel table (daemon/telemetry/telemetry_channels.cpp); see docs/dashboard.md.
// Everything 3D is in the map frame ("map"), so no transforms are needed to view it.
#include <cstdint>
#include <map>
#include <span>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include "common/car.hpp"
#include "common/geometry.hpp"
#include "common/time.hpp"
#include "common/types.hpp"

#include "web/hub.hpp"

namespace fsd::web {

class WebServer;

namespace topics {
inline constexpr const char* kConeMap = "/map/cones";            // foxglove.SceneUpdate, latched
inline constexpr const char* kDetections = "/perception/cones";  // foxglove.SceneUpdate
inline constexpr const char* kCar = "/vehicle/car";              // foxglove.SceneUpdate
inline constexpr const char* kPaths = "/planning/paths";         // foxglove.SceneUpdate, latched
inline constexpr const char* kPointCloud = "/lidar/points";      // foxglove.PointCloud
inline constexpr const char* kCameraImage = "/camera/image";     // foxglove.CompressedImage
// Not advertised: the camera stage does not hand its boxes out yet (an advertised channel must deliver).
inline constexpr const char* kCameraDetections = "/camera/detections";  // foxglove.ImageAnnotations
inline constexpr const char* kVehicleState = "/vehicle/state";          // fsd.VehicleState
inline constexpr const char* kAsStatus = "/as/status";                  // fsd.AsStatus, latched
inline constexpr const char* kFaults = "/faults";                       // fsd.Faults, latched
inline constexpr const char* kLog = "/log";                             // foxglove.Log
// Simulator ground truth (sim runs only), kept apart from the stack's own estimates above.
inline constexpr const char* kTruthCones = "/truth/cones";                 // foxglove.SceneUpdate, latched
inline constexpr const char* kTruthCar = "/truth/car";                     // foxglove.SceneUpdate
inline constexpr const char* kTruthVehicleState = "/truth/vehicle_state";  // fsd.TruthVehicleState
inline constexpr const char* kTruthPath = "/truth/path";                   // foxglove.SceneUpdate, latched
inline constexpr const char* kTruthLocalizationError = "/truth/localization_error";  // fsd.LocalizationError
// The localization's own view of itself (also on the car): its source, quality and covariance; its loop closures.
inline constexpr const char* kLocalization = "/localization/estimate";         // fsd.Localization
inline constexpr const char* kLoopClosures = "/localization/loop_closures";  // fsd.LoopClosures, latched
}  // namespace topics

struct ChannelSpec {
  std::string topic;
  std::string schema_name;
  std::string schema;  // JSON schema text
  ChannelOptions options;
};

// The JSON schemas the channels use (web/channel_schemas.cpp). Which channel carries which is declared in one
// table, the daemon's (daemon/telemetry/telemetry_channels.cpp).
enum class Schema {
  SceneUpdate,        // foxglove.SceneUpdate
  PointCloud,         // foxglove.PointCloud
  CompressedImage,    // foxglove.CompressedImage
  ImageAnnotations,   // foxglove.ImageAnnotations
  Log,                // foxglove.Log
  VehicleState,       // fsd.VehicleState
  TruthVehicleState,  // fsd.TruthVehicleState
  AsStatus,           // fsd.AsStatus
  Faults,             // fsd.Faults
  Localization,       // fsd.Localization
  LocalizationError,  // fsd.LocalizationError
  LoopClosures,       // fsd.LoopClosures
};
ChannelSpec channel_spec(const char* topic, Schema schema, const std::string& description, ChannelOptions options = {});

// The ids the server gave the channels, by topic.
struct ChannelIds {
  std::map<std::string, ChannelId> by_topic;
  ChannelId at(const std::string& topic) const;  // throws std::out_of_range for a topic not added
};
ChannelIds add_channels(WebServer& server, const std::vector<ChannelSpec>& specs);

// ---- payload builders (each returns the JSON text of one message)

// The cone map (map frame) as truncated cylinders in the cone colours, one entity per cone ("cone/<map id>"),
// positions rounded to cm; cone_map_scene is the whole SceneUpdate.
std::vector<nlohmann::json> cone_map_entities(Stamp t, const std::vector<Cone>& cones);
std::string cone_map_scene(Stamp t, const std::vector<Cone>& cones);
// Whether the camera's HOG + SVM verified a detection (stage Camera; the truth source's ideal detector counts too).
bool camera_verified(const Cone& c);
// Detections (vehicle frame) placed in the map by the car's pose, expiring after 0.5 s, in their colours: the
// camera-verified ones as solid boxes (entity "detections"), the LiDAR-only ones as the same boxes half transparent
// with metadata render = outline (entity "detections_unverified"), which the dashboard draws as their wires.
std::string detections_scene(Stamp t, const ConeDetections& detections, const Pose2& car_pose);

struct CarShape {
  double length = 2.9, width = 1.4, height = 1.0;  // m
  double rear_overhang = 0.6;                      // m behind the rear axle (the vehicle frame's origin)
};
CarShape car_shape_of(const CarDescription& car);  // the body of the car's description (car.*)
// The car as a box plus a heading arrow, entity "car".
std::string car_scene(Stamp t, const Pose2& pose, const CarShape& shape = {});

struct PathSet {
  std::vector<Vec2> lap1_trajectory;  // driven in lap 1 (the recorded path of lap 2)
  std::vector<Vec2> lap2_tracking;    // driven while tracking in lap 2
  std::vector<Vec2> planned;          // what the planner asks for now
};
// Line strips decimated to points at least `min_spacing` apart (ends kept), mm on the wire: the driven trails in
// pieces of 100 points ("lap1_trajectory/0", "/1", ..., "lap2_tracking/0", ...; each piece starts at the previous
// one's last point, so only the newest piece changes as the car drives), and "planned_path" at twice the spacing.
// An empty path has no entity. paths_scene is the whole SceneUpdate.
std::vector<nlohmann::json> paths_entities(Stamp t, const PathSet& paths, double min_spacing = 0.25);
std::string paths_scene(Stamp t, const PathSet& paths, double min_spacing = 0.25);

struct CloudOptions {
  std::size_t max_points = 5000;  // uniform decimation beyond this (5000 points ≈ 110 kB of JSON)
};
// Points (in the frame whose pose in the map is `origin`) with fields x, y, z (float32), intensity (uint8) and
// ground (uint8: 1 ground, 0 not), 16 bytes per point, base64 in "data".
std::string point_cloud(Stamp t, const Pose3& origin, std::span<const Point> ground, std::span<const Point> non_ground,
                        const CloudOptions& options = {});

// An already encoded image ("jpeg", "png" or "webp").
std::string compressed_image(Stamp t, std::span<const std::uint8_t> data, const std::string& format,
                             const std::string& frame_id = "camera");

struct ImageBox {
  double x = 0, y = 0, width = 0, height = 0;  // pixels, top-left origin
  ConeColour colour = ConeColour::Unknown;
  std::string label;  // e.g. "blue 0.93"
};
std::string image_annotations(Stamp t, const std::vector<ImageBox>& boxes);

// Speed, yaw rate, lateral acceleration, sideslip, steering and the target speed: the plots of the dashboard.
std::string vehicle_state_json(const VehicleState& state, double target_speed);

struct AsStatusView {
  AsState as_state = AsState::Off;
  Mission mission = Mission::None;
  int lap = 0;  // the lap being driven (1 on the first; after the finish the last one driven)
  int laps_completed = 0;
  int laps_total = 0;
  std::vector<double> lap_times;  // s, completed laps
  double lap_time = 0;            // s, the lap in progress
  std::string control_mode;       // e.g. "lap 1: midline", "lap 2: stored trajectory"
  bool res_go = false, res_emergency = false, ebs_active = false;
  bool finished = false;
};
std::string as_status_json(Stamp t, const AsStatusView& status);

struct FaultEvent {
  Stamp t = 0;
  std::string source, what, action;
  bool active = true;
};
// The recent faults (the latest `max_items`), newest last.
std::string faults_json(Stamp t, const std::vector<FaultEvent>& faults, std::size_t max_items = 50);

// ---- ground truth of a simulated run (never the stack's estimate)

struct TruthCone {
  Pose3 base = Pose3::Identity();  // centre of the base on the ground; z axis = the cone's axis (tilted when knocked)
  ConeColour colour = ConeColour::Unknown;
  double base_width = 0.228, top_width = 0.0, height = 0.325;  // m
  bool knocked = false;
};
// Standing cones as translucent cylinders in their colours (entity "truth_cones", metadata render=ghost so the
// dashboard draws them as wireframes) and knocked-over ones lying where they fell, in solid magenta (entity
// "truth_knocked_cones"); both carry the count in their metadata.
std::string truth_cones_scene(Stamp t, const std::vector<TruthCone>& cones);
// The true car pose: the footprint outline and a heading arrow (entity "truth_car", render=ghost).
std::string truth_car_scene(Stamp t, const Pose2& pose, const CarShape& shape = {});

struct TruthState {
  Stamp t = 0;
  Pose2 pose;                        // rear-axle centre, map frame
  double speed = 0, vx = 0, vy = 0;  // m/s (vx, vy in the body frame at the CoG)
  double yaw_rate = 0;               // rad/s
  double ax = 0, ay = 0;             // m/s², body frame
  double sideslip = 0;               // rad
  double steering = 0;               // rad, actual front wheel angle
  int cones_hit = 0;
};
std::string truth_state_json(const TruthState& s);

// ---- localization: what the filter says of itself, its error against the truth (sim runs), its loop closures

struct LocalizationView {
  Stamp t = 0;               // the estimate's instant
  std::string source;        // run.localization_source in use
  std::string quality;       // good, degraded, lost ("" when the source has no such verdict)
  std::string gnss;          // the latest GNSS fix's verdict ("" without one)
  bool has_covariance = false;
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();  // over (x, y, yaw), map frame
};
// fsd.Localization: source, quality, gnss; with a covariance position_sigma (m, √ of the larger eigenvalue of the
// position block: the 1σ bound in the worst direction), sigma_x, sigma_y, sigma_yaw and the 3×3 row-major
// covariance; position_sigma is null without one.
std::string localization_json(const LocalizationView& v);

struct LocalizationError {
  Stamp t = 0;
  double position = 0;           // m, |estimate − truth|
  double dx = 0, dy = 0;         // m, map frame
  double along = 0, across = 0;  // m, in the true heading's frame
  double yaw = 0;                // rad, wrapped
  double carried = 0;            // s the estimate was carried forward to the truth's instant
};
// The estimate against the truth at the truth's instant: the estimate carried forward by its own velocity over the
// gap between the two stamps (at most a control cycle or two).
LocalizationError localization_error(const VehicleState& estimate, const TruthState& truth);
std::string localization_error_json(const LocalizationError& e);

struct LoopClosureEvent {
  Stamp t = 0;               // the run clock where the loop closed
  int lap = 0;               // 1 for the first loop
  double x = 0, y = 0;       // m, where the car was (the estimate before the correction)
  double dx = 0, dy = 0;     // m, the correction's translation (map ← estimated)
  double dyaw = 0;           // rad
  int pairs = 0;             // start cones seen again
  double rms = 0;            // m over them
  int cones_merged = 0;
};
// fsd.LoopClosures: every loop closure so far, oldest first, each with its shift (m, |dx, dy|).
std::string loop_closures_json(Stamp t, const std::vector<LoopClosureEvent>& events);

// The true driven path (map frame), white, in pieces as the driven trails ("truth_path/0", ...).
std::vector<nlohmann::json> truth_path_entities(Stamp t, const std::vector<Vec2>& path, double min_spacing = 0.25);

enum class LogLevel : int { Unknown = 0, Debug = 1, Info = 2, Warning = 3, Error = 4, Fatal = 5 };  // foxglove.Log
std::string log_json(Stamp t, LogLevel level, const std::string& name, const std::string& message);

}  // namespace fsd::web
