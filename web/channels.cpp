#include "web/channels.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

#include <Eigen/Eigenvalues>
#include <nlohmann/json.hpp>

#include "web/base64.hpp"
#include "web/scene_delta.hpp"
#include "web/server.hpp"

namespace fsd::web {

using nlohmann::json;

namespace {

constexpr const char* kMapFrame = "map";
constexpr std::size_t kPathPiece = 100;  // points per entity of a driven trail

// Fewer digits on the wire where they mean nothing: n / per_unit is the double nearest to the decimal, which
// nlohmann prints in its shortest exact form (12.35, not 17 digits).
double round_to(double v, double per_unit) { return std::round(v * per_unit) / per_unit; }

json stamp(Stamp t) {
  if (!std::isfinite(t) || t < 0) t = 0;
  auto sec = static_cast<std::int64_t>(std::floor(t));
  auto nsec = static_cast<std::int64_t>(std::llround((t - static_cast<double>(sec)) * 1e9));
  if (nsec >= 1000000000) {
    ++sec;
    nsec -= 1000000000;
  }
  return {{"sec", sec}, {"nsec", nsec}};
}

json duration(double s) { return stamp(s); }
json vec3(double x, double y, double z) { return {{"x", x}, {"y", y}, {"z", z}}; }
json rgba(double r, double g, double b, double a = 1.0) { return {{"r", r}, {"g", g}, {"b", b}, {"a", a}}; }
// To 0.1 mm and 1e-4 of a quaternion (2e-4 rad): 7 characters a number instead of 18, on every box, arrow and cone.
json yaw_pose(double x, double y, double z, double yaw) {
  const auto r = [](double v) { return round_to(v, 10000); };
  return {{"position", vec3(r(x), r(y), r(z))},
          {"orientation", {{"x", 0.0}, {"y", 0.0}, {"z", r(std::sin(yaw / 2))}, {"w", r(std::cos(yaw / 2))}}}};
}
json pose3(const Pose3& p) {
  const Eigen::Quaterniond q(p.linear());
  const auto& t = p.translation();
  return {{"position", vec3(t.x(), t.y(), t.z())},
          {"orientation", {{"x", q.x()}, {"y", q.y()}, {"z", q.z()}, {"w", q.w()}}}};
}

json colour_of(ConeColour c, double alpha = 1.0) {
  switch (c) {
    case ConeColour::Blue:
      return rgba(0.10, 0.35, 0.95, alpha);
    case ConeColour::Yellow:
      return rgba(1.00, 0.85, 0.05, alpha);
    case ConeColour::Orange:
      return rgba(1.00, 0.50, 0.00, alpha);
    case ConeColour::BigOrange:
      return rgba(1.00, 0.35, 0.00, alpha);
    case ConeColour::Red:
      return rgba(0.90, 0.10, 0.10, alpha);
    case ConeColour::Unknown:
      break;
  }
  return rgba(0.60, 0.60, 0.60, alpha);
}

// An entity with every primitive list present, as Foxglove's own messages have them.
json entity(Stamp t, const std::string& id, double lifetime_s = 0.0) {
  return {{"timestamp", stamp(t)},
          {"frame_id", kMapFrame},
          {"id", id},
          {"lifetime", duration(lifetime_s)},
          {"frame_locked", false},
          {"metadata", json::array()},
          {"arrows", json::array()},
          {"cubes", json::array()},
          {"spheres", json::array()},
          {"cylinders", json::array()},
          {"lines", json::array()},
          {"triangles", json::array()},
          {"texts", json::array()},
          {"models", json::array()}};
}

std::string scene(const json& entities) { return json{{"deletions", json::array()}, {"entities", entities}}.dump(); }

json cone_cylinder(const Vec3& p, ConeColour c) {
  const bool big = c == ConeColour::BigOrange;
  const double d = big ? 0.285 : 0.228, h = big ? 0.505 : 0.325;  // FS cone sizes
  return {{"pose", yaw_pose(p.x(), p.y(), p.z() + h / 2, 0.0)},
          {"size", vec3(d, d, h)},
          {"bottom_scale", 1.0},
          {"top_scale", 0.15},
          {"color", colour_of(c)}};
}

std::vector<Vec2> decimate(const std::vector<Vec2>& pts, double min_spacing) {
  std::vector<Vec2> out;
  for (const auto& p : pts) {
    if (!p.allFinite()) continue;
    if (out.empty() || (p - out.back()).norm() >= min_spacing) out.push_back(p);
  }
  if (!pts.empty() && pts.back().allFinite() && !out.empty() && out.back() != pts.back()) out.push_back(pts.back());
  return out;
}

json line_strip(const std::vector<Vec2>& pts, double thickness, const json& colour, double z) {
  json points = json::array();
  for (const auto& p : pts) points.push_back(vec3(round_to(p.x(), 1000), round_to(p.y(), 1000), z));
  return {{"type", 0},
          {"pose", yaw_pose(0, 0, 0, 0)},
          {"thickness", thickness},
          {"scale_invariant", false},
          {"points", std::move(points)},
          {"color", colour},
          {"colors", json::array()},
          {"indices", json::array()}};
}

void put_point(std::uint8_t* out, const Point& p, bool ground) {
  std::memcpy(out, &p.x, 4);
  std::memcpy(out + 4, &p.y, 4);
  std::memcpy(out + 8, &p.z, 4);
  out[12] = static_cast<std::uint8_t>(std::clamp(p.intensity, 0.0f, 255.0f));
  out[13] = ground ? 1 : 0;
  out[14] = out[15] = 0;
}

}  // namespace

ChannelIds add_channels(WebServer& server, const std::vector<ChannelSpec>& specs) {
  ChannelIds ids;
  for (const auto& s : specs) ids.by_topic[s.topic] = server.add_channel(s.topic, s.schema_name, s.schema, s.options);
  return ids;
}

ChannelId ChannelIds::at(const std::string& topic) const {
  const auto it = by_topic.find(topic);
  if (it == by_topic.end()) throw std::out_of_range("web: no channel " + topic);
  return it->second;
}

std::vector<json> cone_map_entities(Stamp t, const std::vector<Cone>& cones) {
  std::vector<json> out;
  for (std::size_t i = 0; i < cones.size(); ++i) {
    const auto& c = cones[i];
    if (!c.position.allFinite()) continue;
    // The map's stable id, so that a client replaces just this cone; a cone without one is named by its place.
    json e = entity(t, c.id ? "cone/" + std::to_string(c.id) : "cone/#" + std::to_string(i));
    // Rounded to cm (a cone is 228 mm wide): the map's sub-cm refinements would resend the cone for nothing.
    const Vec3 p(round_to(c.position.x(), 100), round_to(c.position.y(), 100), round_to(c.position.z(), 100));
    e["cylinders"].push_back(cone_cylinder(p, c.colour));
    out.push_back(std::move(e));
  }
  return out;
}

std::string cone_map_scene(Stamp t, const std::vector<Cone>& cones) {
  return scene_update_json(cone_map_entities(t, cones));
}

bool camera_verified(const Cone& c) { return c.stage == DetectionStage::Camera || c.stage == DetectionStage::Truth; }

std::string detections_scene(Stamp t, const ConeDetections& detections, const Pose2& car_pose) {
  constexpr double kSide = 0.35, kHeight = 0.4;
  json verified = entity(t, "detections", 0.5), unverified = entity(t, "detections_unverified", 0.5);
  verified["cubes"] = json::array();
  unverified["cubes"] = json::array();
  // The LiDAR-only boxes are the same boxes, drawn as their outline by the dashboard (render = outline) and half
  // transparent by other Foxglove clients: a box costs a third of the bytes of its 12 edges as lines, which the
  // Wi-Fi budget needs at 4 Hz.
  unverified["metadata"].push_back({{"key", "render"}, {"value", "outline"}});
  for (const auto& c : detections.cones) {
    if (!c.position.allFinite()) continue;
    const Vec2 m = car_pose.transform(c.position.head<2>());
    // Verified by the camera's HOG + SVM (or the truth source's ideal detector): a solid box in its colour.
    const bool solid = camera_verified(c);
    (solid ? verified : unverified)["cubes"].push_back({{"pose", yaw_pose(m.x(), m.y(), kHeight / 2, car_pose.yaw)},
                                                        {"size", vec3(kSide, kSide, kHeight)},
                                                        {"color", colour_of(c.colour, solid ? 0.85 : 0.5)}});
  }
  return scene(json::array({verified, unverified}));
}

CarShape car_shape_of(const CarDescription& car) {
  CarShape s;
  s.length = car.body_length;
  s.width = car.body_width;
  s.rear_overhang = car.rear_overhang;
  return s;
}

std::string car_scene(Stamp t, const Pose2& pose, const CarShape& shape) {
  json e = entity(t, "car");
  const double ahead = shape.length / 2 - shape.rear_overhang;  // box centre ahead of the rear axle
  const Vec2 centre = pose.transform({ahead, 0.0});
  e["cubes"].push_back({{"pose", yaw_pose(centre.x(), centre.y(), shape.height / 2, pose.yaw)},
                        {"size", vec3(shape.length, shape.width, shape.height)},
                        {"color", rgba(0.85, 0.1, 0.1, 0.9)}});
  e["arrows"].push_back({{"pose", yaw_pose(pose.x, pose.y, shape.height + 0.1, pose.yaw)},
                         {"shaft_length", shape.length * 0.8},
                         {"shaft_diameter", 0.08},
                         {"head_length", 0.4},
                         {"head_diameter", 0.25},
                         {"color", rgba(1, 1, 1, 1)}});
  return scene(json::array({e}));
}

namespace {
// A driven trail as line strips in pieces of kPathPiece points (each starting where the previous one ended), so
// that only the newest piece changes as the car drives on.
void trail_pieces(std::vector<json>& out, Stamp t, const std::vector<Vec2>& path, const std::string& id,
                  double thickness, const json& colour, double z, double min_spacing) {
  const auto pts = decimate(path, min_spacing);
  for (std::size_t first = 0, k = 0; first + 1 < pts.size(); first += kPathPiece, ++k) {
    const std::size_t last = std::min(first + kPathPiece, pts.size() - 1);
    json e = entity(t, id + "/" + std::to_string(k));
    const std::vector<Vec2> piece(pts.begin() + static_cast<std::ptrdiff_t>(first),
                                  pts.begin() + static_cast<std::ptrdiff_t>(last) + 1);
    e["lines"].push_back(line_strip(piece, thickness, colour, z));
    out.push_back(std::move(e));
  }
}
}  // namespace

std::vector<json> paths_entities(Stamp t, const PathSet& paths, double min_spacing) {
  std::vector<json> out;
  const auto pieces = [&](const std::vector<Vec2>& path, const char* id, double thickness, const json& colour,
                          double z) { trail_pieces(out, t, path, id, thickness, colour, z, min_spacing); };
  pieces(paths.lap1_trajectory, "lap1_trajectory", 0.10, rgba(0.2, 0.9, 0.3, 1.0), 0.02);
  pieces(paths.lap2_tracking, "lap2_tracking", 0.10, rgba(0.95, 0.2, 0.9, 1.0), 0.04);
  // The plan changes as a whole at each update: one entity, coarser points.
  const auto planned = decimate(paths.planned, 2 * min_spacing);
  if (planned.size() >= 2) {
    json e = entity(t, "planned_path");
    e["lines"].push_back(line_strip(planned, 0.14, rgba(0.1, 0.9, 0.95, 1.0), 0.06));
    out.push_back(std::move(e));
  }
  return out;
}

std::string paths_scene(Stamp t, const PathSet& paths, double min_spacing) {
  return scene_update_json(paths_entities(t, paths, min_spacing));
}

std::string point_cloud(Stamp t, const Pose3& origin, std::span<const Point> ground, std::span<const Point> non_ground,
                        const CloudOptions& options) {
  constexpr std::size_t kStride = 16;
  const std::size_t total = ground.size() + non_ground.size();
  // Keep every k-th point of both sets so that their proportions stay.
  const std::size_t step =
      total > options.max_points && options.max_points > 0 ? (total + options.max_points - 1) / options.max_points : 1;
  std::vector<std::uint8_t> data;
  data.reserve((total / step + 2) * kStride);
  for (const auto& [points, is_ground] : {std::pair{ground, true}, std::pair{non_ground, false}}) {
    for (std::size_t i = 0; i < points.size(); i += step) {
      const Point& p = points[i];
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) continue;
      data.resize(data.size() + kStride);
      put_point(data.data() + data.size() - kStride, p, is_ground);
    }
  }
  json fields = json::array({{{"name", "x"}, {"offset", 0}, {"type", 7}},
                             {{"name", "y"}, {"offset", 4}, {"type", 7}},
                             {{"name", "z"}, {"offset", 8}, {"type", 7}},
                             {{"name", "intensity"}, {"offset", 12}, {"type", 1}},
                             {{"name", "ground"}, {"offset", 13}, {"type", 1}}});
  return json{{"timestamp", stamp(t)},   {"frame_id", kMapFrame},       {"pose", pose3(origin)},
              {"point_stride", kStride}, {"fields", std::move(fields)}, {"data", base64_encode(data)}}
      .dump();
}

std::string compressed_image(Stamp t, std::span<const std::uint8_t> data, const std::string& format,
                             const std::string& frame_id) {
  return json{{"timestamp", stamp(t)}, {"frame_id", frame_id}, {"data", base64_encode(data)}, {"format", format}}
      .dump();
}

std::string image_annotations(Stamp t, const std::vector<ImageBox>& boxes) {
  json points = json::array(), texts = json::array();
  for (const auto& b : boxes) {
    const double x0 = b.x, y0 = b.y, x1 = b.x + b.width, y1 = b.y + b.height;
    points.push_back(
        {{"timestamp", stamp(t)},
         {"type", 2},
         {"points",
          json::array(
              {{{"x", x0}, {"y", y0}}, {{"x", x1}, {"y", y0}}, {{"x", x1}, {"y", y1}}, {{"x", x0}, {"y", y1}}})},
         {"outline_color", colour_of(b.colour)},
         {"outline_colors", json::array()},
         {"fill_color", rgba(0, 0, 0, 0)},
         {"thickness", 2.0}});
    if (!b.label.empty())
      texts.push_back({{"timestamp", stamp(t)},
                       {"position", {{"x", x0}, {"y", y0 - 4}}},
                       {"text", b.label},
                       {"font_size", 14.0},
                       {"text_color", rgba(1, 1, 1, 1)},
                       {"background_color", rgba(0, 0, 0, 0.6)}});
  }
  return json{{"circles", json::array()}, {"points", std::move(points)}, {"texts", std::move(texts)}}.dump(
      -1, ' ', false, json::error_handler_t::replace);
}

std::string vehicle_state_json(const VehicleState& s, double target_speed) {
  return json{{"timestamp", stamp(s.stamp)},
              {"x", s.pose.x},
              {"y", s.pose.y},
              {"yaw", s.pose.yaw},
              {"speed", s.speed()},
              {"vx", s.vx},
              {"vy", s.vy},
              {"yaw_rate", s.yaw_rate},
              {"lateral_acceleration", s.ay},
              {"longitudinal_acceleration", s.ax},
              {"sideslip", s.sideslip()},
              {"steering", s.steering},
              {"target_speed", target_speed}}
      .dump();
}

std::string truth_cones_scene(Stamp t, const std::vector<TruthCone>& cones) {
  json standing = entity(t, "truth_cones"), knocked = entity(t, "truth_knocked_cones");
  for (const auto& c : cones) {
    const Vec3 axis = c.base.linear().col(2);
    const Vec3 centre = c.base.translation() + axis * (c.height / 2);
    if (!centre.allFinite()) continue;
    Pose3 p = c.base;
    p.translation() = centre;
    const double d = c.base_width;
    json cyl = {{"pose", pose3(p)},
                {"size", vec3(d, d, c.height)},
                {"bottom_scale", 1.0},
                {"top_scale", d > 0 ? std::clamp(c.top_width / d, 0.0, 1.0) : 1.0},
                {"color", c.knocked ? rgba(1.0, 0.1, 0.8, 1.0) : colour_of(c.colour, 0.35)}};
    (c.knocked ? knocked : standing)["cylinders"].push_back(std::move(cyl));
  }
  for (json* e : {&standing, &knocked}) {
    (*e)["metadata"].push_back({{"key", "source"}, {"value", "simulator ground truth"}});
    (*e)["metadata"].push_back({{"key", "count"}, {"value", std::to_string((*e)["cylinders"].size())}});
  }
  standing["metadata"].push_back({{"key", "render"}, {"value", "ghost"}});
  return scene(json::array({standing, knocked}));
}

std::string truth_car_scene(Stamp t, const Pose2& pose, const CarShape& shape) {
  json e = entity(t, "truth_car");
  const double back = -shape.rear_overhang, front = shape.length - shape.rear_overhang, half = shape.width / 2;
  json points = json::array();
  for (const Vec2& corner : {Vec2(back, -half), Vec2(front, -half), Vec2(front, half), Vec2(back, half)}) {
    const Vec2 m = pose.transform(corner);
    points.push_back(vec3(m.x(), m.y(), 0.05));
  }
  e["lines"].push_back({{"type", 1},  // LINE_LOOP: the footprint
                        {"pose", yaw_pose(0, 0, 0, 0)},
                        {"thickness", 0.12},
                        {"scale_invariant", false},
                        {"points", std::move(points)},
                        {"color", rgba(1.0, 1.0, 1.0, 1.0)},
                        {"colors", json::array()},
                        {"indices", json::array()}});
  e["arrows"].push_back({{"pose", yaw_pose(pose.x, pose.y, 0.08, pose.yaw)},
                         {"shaft_length", shape.length * 0.6},
                         {"shaft_diameter", 0.05},
                         {"head_length", 0.35},
                         {"head_diameter", 0.2},
                         {"color", rgba(1.0, 1.0, 1.0, 1.0)}});
  e["metadata"].push_back({{"key", "source"}, {"value", "simulator ground truth"}});
  e["metadata"].push_back({{"key", "render"}, {"value", "ghost"}});
  return scene(json::array({e}));
}

std::string truth_state_json(const TruthState& s) {
  return json{{"timestamp", stamp(s.t)},
              {"source", "simulator ground truth"},
              {"x", s.pose.x},
              {"y", s.pose.y},
              {"yaw", s.pose.yaw},
              {"speed", s.speed},
              {"vx", s.vx},
              {"vy", s.vy},
              {"yaw_rate", s.yaw_rate},
              {"lateral_acceleration", s.ay},
              {"longitudinal_acceleration", s.ax},
              {"sideslip", s.sideslip},
              {"steering", s.steering},
              {"cones_hit", s.cones_hit}}
      .dump();
}

std::string as_status_json(Stamp t, const AsStatusView& s) {
  return json{{"timestamp", stamp(t)},
              {"as_state", std::string(to_string(s.as_state))},
              {"mission", std::string(to_string(s.mission))},
              {"lap", s.lap},
              {"laps_completed", s.laps_completed},
              {"laps_total", s.laps_total},
              {"lap_times", s.lap_times},
              {"lap_time", s.lap_time},
              {"control_mode", s.control_mode},
              {"res_go", s.res_go},
              {"res_emergency", s.res_emergency},
              {"ebs_active", s.ebs_active},
              {"finished", s.finished}}
      .dump(-1, ' ', false, json::error_handler_t::replace);
}

std::string faults_json(Stamp t, const std::vector<FaultEvent>& faults, std::size_t max_items) {
  json list = json::array();
  const std::size_t first = faults.size() > max_items ? faults.size() - max_items : 0;
  for (std::size_t i = first; i < faults.size(); ++i) {
    const auto& f = faults[i];
    list.push_back({{"t", f.t}, {"source", f.source}, {"what", f.what}, {"action", f.action}, {"active", f.active}});
  }
  return json{{"timestamp", stamp(t)}, {"faults", std::move(list)}}.dump(-1, ' ', false,
                                                                         json::error_handler_t::replace);
}

std::string log_json(Stamp t, LogLevel level, const std::string& name, const std::string& message) {
  return json{{"timestamp", stamp(t)},
              {"level", static_cast<int>(level)},
              {"message", message},
              {"name", name},
              {"file", ""},
              {"line", 0}}
      .dump(-1, ' ', false, json::error_handler_t::replace);
}

// ---- localization

std::string localization_json(const LocalizationView& v) {
  const Eigen::Matrix3d& P = v.covariance;
  json j{{"timestamp", stamp(v.t)}, {"source", v.source}, {"quality", v.quality}, {"gnss", v.gnss}};
  if (v.has_covariance && P.allFinite()) {
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(P.topLeftCorner<2, 2>());
    const double largest = std::max(0.0, eig.eigenvalues().maxCoeff());
    j["position_sigma"] = std::sqrt(largest);
    j["sigma_x"] = std::sqrt(std::max(0.0, P(0, 0)));
    j["sigma_y"] = std::sqrt(std::max(0.0, P(1, 1)));
    j["sigma_yaw"] = std::sqrt(std::max(0.0, P(2, 2)));
    j["covariance"] = {P(0, 0), P(0, 1), P(0, 2), P(1, 0), P(1, 1), P(1, 2), P(2, 0), P(2, 1), P(2, 2)};
  } else {
    j["position_sigma"] = nullptr;
  }
  return j.dump();
}

LocalizationError localization_error(const VehicleState& estimate, const TruthState& truth) {
  // The estimate carried to the truth's instant with its own velocity (the state is up to a cycle older).
  const double dt = truth.t - estimate.stamp;
  const double c = std::cos(estimate.pose.yaw), s = std::sin(estimate.pose.yaw);
  const double x = estimate.pose.x + (estimate.vx * c - estimate.vy * s) * dt;
  const double y = estimate.pose.y + (estimate.vx * s + estimate.vy * c) * dt;
  const double yaw = estimate.pose.yaw + estimate.yaw_rate * dt;
  LocalizationError e;
  e.t = truth.t;
  e.dx = x - truth.pose.x;
  e.dy = y - truth.pose.y;
  e.position = std::hypot(e.dx, e.dy);
  const double ct = std::cos(truth.pose.yaw), st = std::sin(truth.pose.yaw);
  e.along = e.dx * ct + e.dy * st;
  e.across = -e.dx * st + e.dy * ct;
  e.yaw = wrap_angle(yaw - truth.pose.yaw);
  e.carried = dt;
  return e;
}

std::string localization_error_json(const LocalizationError& e) {
  return json{{"timestamp", stamp(e.t)},
              {"source", "estimate against the simulator ground truth"},
              {"position_error", e.position},
              {"dx", e.dx},
              {"dy", e.dy},
              {"along", e.along},
              {"across", e.across},
              {"yaw_error", e.yaw},
              {"carried", e.carried}}
      .dump();
}

std::string loop_closures_json(Stamp t, const std::vector<LoopClosureEvent>& events) {
  json list = json::array();
  for (const auto& e : events)
    list.push_back({{"t", e.t},
                    {"lap", e.lap},
                    {"x", e.x},
                    {"y", e.y},
                    {"dx", e.dx},
                    {"dy", e.dy},
                    {"dyaw", e.dyaw},
                    {"shift", std::hypot(e.dx, e.dy)},
                    {"pairs", e.pairs},
                    {"rms", e.rms},
                    {"cones_merged", e.cones_merged}});
  return json{{"timestamp", stamp(t)}, {"loop_closures", std::move(list)}}.dump();
}

std::vector<json> truth_path_entities(Stamp t, const std::vector<Vec2>& path, double min_spacing) {
  std::vector<json> out;
  trail_pieces(out, t, path, "truth_path", 0.06, rgba(0.96, 0.96, 0.96, 1.0), 0.08, min_spacing);
  return out;
}

}  // namespace fsd::web
