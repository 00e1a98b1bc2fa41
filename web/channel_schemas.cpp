// JSON schemas of the standard channels. The foxglove.* ones describe the fields our builders fill, with the
// names and types of the Foxglove schemas so that Foxglove Studio's panels understand them (bytes are base64
// strings marked contentEncoding "base64", times are {sec, nsec} objects titled "time").
#include <nlohmann/json.hpp>

#include "web/channels.hpp"

namespace fsd::web {

using nlohmann::json;

namespace {

json num(const std::string& description) { return {{"type", "number"}, {"description", description}}; }
json integer(const std::string& description) { return {{"type", "integer"}, {"description", description}}; }
json str(const std::string& description) { return {{"type", "string"}, {"description", description}}; }
json boolean(const std::string& description) { return {{"type", "boolean"}, {"description", description}}; }
json bytes(const std::string& description) {
  return {{"type", "string"}, {"contentEncoding", "base64"}, {"description", description}};
}
json array_of(const json& items, const std::string& description) {
  return {{"type", "array"}, {"items", items}, {"description", description}};
}
json object(const std::string& title, json properties) {
  return {{"title", title}, {"type", "object"}, {"properties", std::move(properties)}};
}
json time_type(const char* title = "time") {
  return {{"type", "object"},
          {"title", title},
          {"properties",
           {{"sec", {{"type", "integer"}, {"minimum", 0}}},
            {"nsec", {{"type", "integer"}, {"minimum", 0}, {"maximum", 999999999}}}}}};
}
json xyz(const char* title) { return object(title, {{"x", num("x")}, {"y", num("y")}, {"z", num("z")}}); }
json xy() { return object("foxglove.Point2", {{"x", num("x, pixels")}, {"y", num("y, pixels")}}); }
json quaternion() {
  return object("foxglove.Quaternion", {{"x", num("x")}, {"y", num("y")}, {"z", num("z")}, {"w", num("w")}});
}
json pose() { return object("foxglove.Pose", {{"position", xyz("foxglove.Vector3")}, {"orientation", quaternion()}}); }
json colour() {
  return object("foxglove.Color",
                {{"r", num("red 0..1")}, {"g", num("green 0..1")}, {"b", num("blue 0..1")}, {"a", num("alpha 0..1")}});
}
json with_schema(json schema, const std::string& description) {
  schema["$schema"] = "https://json-schema.org/draft/2020-12/schema";
  schema["description"] = description;
  return schema;
}

json scene_update() {
  const json primitive_sized =
      object("foxglove.CubePrimitive", {{"pose", pose()}, {"size", xyz("foxglove.Vector3")}, {"color", colour()}});
  const json cylinder = object("foxglove.CylinderPrimitive", {{"pose", pose()},
                                                              {"size", xyz("foxglove.Vector3")},
                                                              {"bottom_scale", num("bottom face scale 0..1")},
                                                              {"top_scale", num("top face scale 0..1")},
                                                              {"color", colour()}});
  const json arrow = object("foxglove.ArrowPrimitive", {{"pose", pose()},
                                                        {"shaft_length", num("m")},
                                                        {"shaft_diameter", num("m")},
                                                        {"head_length", num("m")},
                                                        {"head_diameter", num("m")},
                                                        {"color", colour()}});
  const json line = object("foxglove.LinePrimitive", {{"type", integer("0 LINE_STRIP, 1 LINE_LOOP, 2 LINE_LIST")},
                                                      {"pose", pose()},
                                                      {"thickness", num("m, or pixels when scale_invariant")},
                                                      {"scale_invariant", boolean("thickness in pixels")},
                                                      {"points", array_of(xyz("foxglove.Point3"), "vertices")},
                                                      {"color", colour()},
                                                      {"colors", array_of(colour(), "per-vertex colours (unused)")},
                                                      {"indices", array_of(json{{"type", "integer"}}, "unused")}});
  const json unused = array_of(json{{"type", "object"}}, "not used by fsd");
  const json entity =
      object("foxglove.SceneEntity",
             {{"timestamp", time_type()},
              {"frame_id", str("frame of reference: map")},
              {"id", str("entity id; replaces the previous entity of the same id")},
              {"lifetime", time_type("duration")},
              {"frame_locked", boolean("follow frame_id")},
              {"metadata",
               array_of(object("foxglove.KeyValuePair", {{"key", str("key")}, {"value", str("value")}}), "metadata")},
              {"arrows", array_of(arrow, "arrows")},
              {"cubes", array_of(primitive_sized, "boxes")},
              {"spheres", unused},
              {"cylinders", array_of(cylinder, "cylinders and cones")},
              {"lines", array_of(line, "line strips")},
              {"triangles", unused},
              {"texts", unused},
              {"models", unused}});
  const json deletion =
      object("foxglove.SceneEntityDeletion",
             {{"timestamp", time_type()}, {"type", integer("0 MATCHING_ID, 1 ALL")}, {"id", str("entity id")}});
  return object("foxglove.SceneUpdate",
                {{"deletions", array_of(deletion, "deletions")}, {"entities", array_of(entity, "entities")}});
}

json point_cloud() {
  const json field =
      object("foxglove.PackedElementField", {{"name", str("field name")},
                                             {"offset", integer("byte offset in a point")},
                                             {"type", integer("1 UINT8, 7 FLOAT32 (foxglove.NumericType)")}});
  return object("foxglove.PointCloud", {{"timestamp", time_type()},
                                        {"frame_id", str("map")},
                                        {"pose", pose()},
                                        {"point_stride", integer("bytes per point")},
                                        {"fields", array_of(field, "x, y, z, intensity, ground")},
                                        {"data", bytes("packed points, little-endian")}});
}

json compressed_image() {
  return object("foxglove.CompressedImage", {{"timestamp", time_type()},
                                             {"frame_id", str("camera")},
                                             {"data", bytes("encoded image")},
                                             {"format", str("jpeg, png or webp")}});
}

// The schema of /camera/detections, kept for when the camera stage hands its boxes to the telemetry (the channel
// is not in the channel table until then).
json image_annotations() {
  const json points = object("foxglove.PointsAnnotation", {{"timestamp", time_type()},
                                                           {"type", integer("2 LINE_LOOP")},
                                                           {"points", array_of(xy(), "corners")},
                                                           {"outline_color", colour()},
                                                           {"outline_colors", array_of(colour(), "unused")},
                                                           {"fill_color", colour()},
                                                           {"thickness", num("pixels")}});
  const json text = object("foxglove.TextAnnotation", {{"timestamp", time_type()},
                                                       {"position", xy()},
                                                       {"text", str("label")},
                                                       {"font_size", num("pixels")},
                                                       {"text_color", colour()},
                                                       {"background_color", colour()}});
  return object("foxglove.ImageAnnotations", {{"circles", array_of(json{{"type", "object"}}, "unused")},
                                              {"points", array_of(points, "boxes")},
                                              {"texts", array_of(text, "labels")}});
}

json log() {
  return object("foxglove.Log", {{"timestamp", time_type()},
                                 {"level", integer("0 UNKNOWN, 1 DEBUG, 2 INFO, 3 WARNING, 4 ERROR, 5 FATAL")},
                                 {"message", str("text")},
                                 {"name", str("component")},
                                 {"file", str("source file")},
                                 {"line", integer("source line")}});
}

json vehicle_state() {
  return object("fsd.VehicleState", {{"timestamp", time_type()},
                                     {"x", num("m, rear-axle centre in the map (local ENU)")},
                                     {"y", num("m")},
                                     {"yaw", num("rad, ENU")},
                                     {"speed", num("m/s")},
                                     {"vx", num("m/s, body frame")},
                                     {"vy", num("m/s, body frame")},
                                     {"yaw_rate", num("rad/s")},
                                     {"lateral_acceleration", num("m/s², body frame")},
                                     {"longitudinal_acceleration", num("m/s², body frame")},
                                     {"sideslip", num("rad, atan2(vy, vx)")},
                                     {"steering", num("rad, front wheel angle, left positive")},
                                     {"target_speed", num("m/s, commanded")}});
}

json truth_state() {
  return object("fsd.TruthVehicleState",
                {{"timestamp", time_type()},
                 {"source", str("always \"simulator ground truth\"")},
                 {"x", num("m, true rear-axle centre in the map (local ENU)")},
                 {"y", num("m")},
                 {"yaw", num("rad, ENU")},
                 {"speed", num("m/s, true")},
                 {"vx", num("m/s, body frame at the CoG")},
                 {"vy", num("m/s, body frame at the CoG")},
                 {"yaw_rate", num("rad/s")},
                 {"lateral_acceleration", num("m/s², body frame, as an IMU at the CoG measures it")},
                 {"longitudinal_acceleration", num("m/s², body frame")},
                 {"sideslip", num("rad, at the CoG (0 below walking speed)")},
                 {"steering", num("rad, actual front wheel angle, left positive")},
                 {"cones_hit", integer("cones the car has knocked over")}});
}

json as_status() {
  return object("fsd.AsStatus",
                {{"timestamp", time_type()},
                 {"as_state", str("Off, Ready, Driving, Emergency, Finished")},
                 {"mission", str("mission name")},
                 {"lap", integer("the lap being driven (1 on the first; after the finish the last one driven)")},
                 {"laps_completed", integer("laps completed")},
                 {"laps_total", integer("laps of the mission")},
                 {"lap_times", array_of(json{{"type", "number"}}, "s, completed laps")},
                 {"lap_time", num("s, the lap in progress")},
                 {"control_mode", str("what steers the car now")},
                 {"res_go", boolean("RES go received")},
                 {"res_emergency", boolean("RES emergency pressed")},
                 {"ebs_active", boolean("emergency brake engaged")},
                 {"finished", boolean("mission finished")}});
}

json faults() {
  const json fault = object("fsd.Fault", {{"t", num("s, run clock")},
                                          {"source", str("component")},
                                          {"what", str("what went wrong")},
                                          {"action", str("what the stack did")},
                                          {"active", boolean("still present")}});
  return object("fsd.Faults", {{"timestamp", time_type()}, {"faults", array_of(fault, "recent faults, newest last")}});
}

json localization() {
  return object(
      "fsd.Localization",
      {{"timestamp", time_type()},
       {"source", str("run.localization_source in use: fused, lidar_odometry, gnss, truth")},
       {"quality", str("good, degraded, lost; empty when the source gives no verdict")},
       {"gnss", str("the latest GNSS fix's verdict; empty without one")},
       {"position_sigma", num("m, 1-sigma position bound: the square root of the larger eigenvalue of the position "
                              "covariance; null when the source has no covariance")},
       {"sigma_x", num("m, square root of the covariance's x variance")},
       {"sigma_y", num("m")},
       {"sigma_yaw", num("rad")},
       {"covariance", array_of(json{{"type", "number"}}, "3x3 row-major over (x m, y m, yaw rad), map frame")}});
}

json localization_error() {
  return object("fsd.LocalizationError",
                {{"timestamp", time_type()},
                 {"source", str("always \"estimate against the simulator ground truth\"")},
                 {"position_error", num("m, distance from the estimated to the true rear-axle centre")},
                 {"dx", num("m, estimate minus truth, map frame")},
                 {"dy", num("m")},
                 {"along", num("m, along the true heading (+ ahead)")},
                 {"across", num("m, across the true heading (+ left)")},
                 {"yaw_error", num("rad, estimate minus truth, wrapped")},
                 {"carried", num("s the estimate was carried forward by its velocity to the truth's instant")}});
}

json loop_closures() {
  const json event = object("fsd.LoopClosure", {{"t", num("s, run clock")},
                                                {"lap", integer("1 for the first loop")},
                                                {"x", num("m, where the car was (estimate before the correction)")},
                                                {"y", num("m")},
                                                {"dx", num("m, the correction's translation, map frame")},
                                                {"dy", num("m")},
                                                {"dyaw", num("rad, the correction's rotation")},
                                                {"shift", num("m, |dx, dy|")},
                                                {"pairs", integer("start cones seen again")},
                                                {"rms", num("m over those pairs")},
                                                {"cones_merged", integer("mapped twice, one cone again")}});
  return object("fsd.LoopClosures",
                {{"timestamp", time_type()}, {"loop_closures", array_of(event, "every loop closure, oldest first")}});
}

}  // namespace

ChannelSpec channel_spec(const char* topic, Schema kind, const std::string& description, ChannelOptions options) {
  json schema;
  switch (kind) {
    case Schema::SceneUpdate:
      schema = scene_update();
      break;
    case Schema::PointCloud:
      schema = point_cloud();
      break;
    case Schema::CompressedImage:
      schema = compressed_image();
      break;
    case Schema::ImageAnnotations:
      schema = image_annotations();
      break;
    case Schema::Log:
      schema = log();
      break;
    case Schema::VehicleState:
      schema = vehicle_state();
      break;
    case Schema::TruthVehicleState:
      schema = truth_state();
      break;
    case Schema::AsStatus:
      schema = as_status();
      break;
    case Schema::Faults:
      schema = faults();
      break;
    case Schema::Localization:
      schema = localization();
      break;
    case Schema::LocalizationError:
      schema = localization_error();
      break;
    case Schema::LoopClosures:
      schema = loop_closures();
      break;
  }
  return {topic, schema["title"].get<std::string>(), with_schema(schema, description).dump(), options};
}

}  // namespace fsd::web
