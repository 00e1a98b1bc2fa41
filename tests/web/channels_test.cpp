// Payload builders against hand-computed values: geometry, colours, packed point bytes, timestamps.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <numbers>
#include <set>

#include <nlohmann/json.hpp>

#include "tests/cone_at.hpp"
#include "web/base64.hpp"
#include "web/channels.hpp"

namespace fsd::web {
namespace {

using nlohmann::json;

// An independent decoder for the test.
std::vector<std::uint8_t> unbase64(const std::string& s) {
  auto val = [](char c) -> int {
    if (c >= 'A' && c <= 'Z') return c - 'A';
    if (c >= 'a' && c <= 'z') return c - 'a' + 26;
    if (c >= '0' && c <= '9') return c - '0' + 52;
    return c == '+' ? 62 : 63;
  };
  std::vector<std::uint8_t> out;
  for (std::size_t i = 0; i + 4 <= s.size(); i += 4) {
    const int n = (val(s[i]) << 18) | (val(s[i + 1]) << 12) | ((s[i + 2] == '=' ? 0 : val(s[i + 2])) << 6) |
                  (s[i + 3] == '=' ? 0 : val(s[i + 3]));
    out.push_back(static_cast<std::uint8_t>(n >> 16));
    if (s[i + 2] != '=') out.push_back(static_cast<std::uint8_t>(n >> 8));
    if (s[i + 3] != '=') out.push_back(static_cast<std::uint8_t>(n));
  }
  return out;
}

std::vector<std::uint8_t> bytes(const std::string& s) { return {s.begin(), s.end()}; }

TEST(Base64, Rfc4648Vectors) {
  EXPECT_EQ(base64_encode(bytes("")), "");
  EXPECT_EQ(base64_encode(bytes("f")), "Zg==");
  EXPECT_EQ(base64_encode(bytes("fo")), "Zm8=");
  EXPECT_EQ(base64_encode(bytes("foo")), "Zm9v");
  EXPECT_EQ(base64_encode(bytes("foob")), "Zm9vYg==");
  EXPECT_EQ(base64_encode(bytes("fooba")), "Zm9vYmE=");
  EXPECT_EQ(base64_encode(bytes("foobar")), "Zm9vYmFy");
  const std::vector<std::uint8_t> high{0xff, 0xfe, 0xfd};
  EXPECT_EQ(base64_encode(high), "//79");
}

const auto cone = test::cone_at;

TEST(Channels, ConeMapAsColouredTruncatedCylindersOneEntityPerCone) {
  auto blue = cone(1, 2, ConeColour::Blue), yellow = cone(3.004, -2, ConeColour::Yellow);
  blue.id = 7;
  yellow.id = 9;
  const auto j = json::parse(cone_map_scene(12.25, {blue, yellow, cone(0, 0, ConeColour::BigOrange)}));
  EXPECT_EQ(j["deletions"].size(), 0u);
  ASSERT_EQ(j["entities"].size(), 3u);
  const auto& e = j["entities"][0];
  EXPECT_EQ(e["frame_id"], "map");
  EXPECT_EQ(e["id"], "cone/7");  // the map's id, so a client replaces just this cone
  EXPECT_EQ(j["entities"][1]["id"], "cone/9");
  EXPECT_EQ(j["entities"][2]["id"], "cone/#2");  // no map id (0): named by its place in the list
  EXPECT_EQ(e["timestamp"], (json{{"sec", 12}, {"nsec", 250000000}}));
  ASSERT_EQ(e["cylinders"].size(), 1u);
  const auto& b = e["cylinders"][0];
  EXPECT_DOUBLE_EQ(b["pose"]["position"]["x"].get<double>(), 1.0);
  EXPECT_DOUBLE_EQ(b["pose"]["position"]["z"].get<double>(), 0.325 / 2);  // centre of a 325 mm cone
  EXPECT_DOUBLE_EQ(b["size"]["x"].get<double>(), 0.228);
  EXPECT_GT(b["color"]["b"].get<double>(), b["color"]["r"].get<double>());
  const auto& y = j["entities"][1]["cylinders"][0];
  EXPECT_GT(y["color"]["r"].get<double>(), y["color"]["b"].get<double>());
  EXPECT_EQ(y["pose"]["position"]["x"].get<double>(), 3.0);                       // to the cm
  EXPECT_EQ(j["entities"][2]["cylinders"][0]["size"]["z"].get<double>(), 0.505);  // big orange
}

TEST(Channels, DetectionsArePlacedInTheMapByTheCarPose) {
  ConeDetections d;
  d.cones = {cone(2, 0, ConeColour::Blue), cone(1, 1, ConeColour::Yellow)};
  const auto j = json::parse(detections_scene(1.0, d, Pose2{10, 5, std::numbers::pi / 2}));
  const auto& e = j["entities"][0];
  EXPECT_EQ(e["lifetime"], (json{{"sec", 0}, {"nsec", 500000000}}));
  ASSERT_EQ(e["cubes"].size(), 2u);
  EXPECT_NEAR(e["cubes"][0]["pose"]["position"]["x"].get<double>(), 10.0, 1e-9);  // 2 m ahead = +y in the map
  EXPECT_NEAR(e["cubes"][0]["pose"]["position"]["y"].get<double>(), 7.0, 1e-9);
  EXPECT_NEAR(e["cubes"][1]["pose"]["position"]["x"].get<double>(), 9.0, 1e-9);  // 1 m left = −x
  EXPECT_NEAR(e["cubes"][1]["pose"]["position"]["y"].get<double>(), 6.0, 1e-9);
}

TEST(Channels, CarBoxSitsAheadOfTheRearAxle) {
  CarShape shape;  // 2.9 m long, 0.6 m behind the rear axle: centre 0.85 m ahead
  const auto j = json::parse(car_scene(0, Pose2{10, 5, std::numbers::pi / 2}, shape));
  const auto& cube = j["entities"][0]["cubes"][0];
  EXPECT_NEAR(cube["pose"]["position"]["x"].get<double>(), 10.0, 1e-9);
  EXPECT_NEAR(cube["pose"]["position"]["y"].get<double>(), 5.85, 1e-9);
  EXPECT_NEAR(cube["pose"]["orientation"]["z"].get<double>(), std::sin(std::numbers::pi / 4), 1e-4);  // sent to 1e-4
  EXPECT_NEAR(cube["pose"]["orientation"]["w"].get<double>(), std::cos(std::numbers::pi / 4), 1e-4);
  EXPECT_DOUBLE_EQ(cube["size"]["x"].get<double>(), 2.9);
}

TEST(Channels, PathsAreDecimatedLineStripsKeepingTheEnds) {
  PathSet p;
  for (int i = 0; i <= 10; ++i) p.lap1_trajectory.emplace_back(0.1 * i, 0.0);
  p.planned = {{0, 0}, {5, 5}};
  const auto j = json::parse(paths_scene(0, p, 0.25));
  ASSERT_EQ(j["entities"].size(), 2u);  // no lap-2 trail yet: no entity
  EXPECT_EQ(j["entities"][0]["id"], "lap1_trajectory/0");
  const auto& pts = j["entities"][0]["lines"][0]["points"];
  ASSERT_EQ(pts.size(), 5u);                  // 0, 0.3, 0.6, 0.9 and the end 1.0
  EXPECT_EQ(pts[1]["x"].get<double>(), 0.3);  // to the mm: 0.30000000000000004 would cost 19 bytes
  EXPECT_EQ(pts[4]["x"].get<double>(), 1.0);
  EXPECT_EQ(j["entities"][0]["lines"][0]["type"], 0);  // LINE_STRIP
  EXPECT_EQ(j["entities"][1]["id"], "planned_path");
  EXPECT_EQ(j["entities"][1]["lines"][0]["points"].size(), 2u);
}

TEST(Channels, ADrivenTrailIsCutIntoPiecesOfWhichOnlyTheNewestChangesAsItGrows) {
  PathSet p;
  for (int i = 0; i < 250; ++i) p.lap1_trajectory.emplace_back(1.0 * i, 0.0);  // 250 points 1 m apart
  const auto before = paths_entities(0, p);
  ASSERT_EQ(before.size(), 3u);  // points 0-100, 100-200, 200-249
  EXPECT_EQ(before[0]["id"], "lap1_trajectory/0");
  EXPECT_EQ(before[2]["id"], "lap1_trajectory/2");
  const auto& first = before[0]["lines"][0]["points"];
  ASSERT_EQ(first.size(), 101u);
  EXPECT_EQ(first[100]["x"].get<double>(), 100.0);
  EXPECT_EQ(before[1]["lines"][0]["points"][0]["x"].get<double>(), 100.0);  // continues where the first ended
  EXPECT_EQ(before[2]["lines"][0]["points"].size(), 50u);
  for (int i = 250; i < 260; ++i) p.lap1_trajectory.emplace_back(1.0 * i, 0.0);
  const auto after = paths_entities(0, p);
  ASSERT_EQ(after.size(), 3u);
  EXPECT_EQ(after[0], before[0]);
  EXPECT_EQ(after[1], before[1]);
  EXPECT_EQ(after[2]["lines"][0]["points"].size(), 60u);
}

TEST(Channels, PointCloudPacksSixteenBytesPerPoint) {
  std::vector<Point> ground(2), objects(3);
  ground[0] = {1.5f, -2.0f, 0.0f, 7.0f};
  ground[1] = {2.5f, 0.0f, 0.01f, 300.0f};  // intensity clamps to 255
  objects[0] = {4.0f, 1.0f, 0.3f, 40.0f};
  objects[1] = {5.0f, 1.0f, 0.3f, 0.0f};
  objects[2] = {6.0f, 1.0f, 0.3f, 0.0f};
  Pose3 origin = Pose3::Identity();
  origin.translation() = Vec3(10, 20, 0.5);
  auto j = json::parse(point_cloud(3.0, origin, ground, objects));
  EXPECT_EQ(j["frame_id"], "map");
  EXPECT_EQ(j["point_stride"], 16);
  EXPECT_DOUBLE_EQ(j["pose"]["position"]["y"].get<double>(), 20.0);
  EXPECT_DOUBLE_EQ(j["pose"]["orientation"]["w"].get<double>(), 1.0);
  std::set<std::string> names;
  for (const auto& f : j["fields"]) names.insert(f["name"]);
  EXPECT_EQ(names, (std::set<std::string>{"x", "y", "z", "intensity", "ground"}));
  const auto data = unbase64(j["data"]);
  ASSERT_EQ(data.size(), 5u * 16u);
  float x, y;
  std::memcpy(&x, &data[0], 4);
  std::memcpy(&y, &data[4], 4);
  EXPECT_EQ(x, 1.5f);
  EXPECT_EQ(y, -2.0f);
  EXPECT_EQ(data[12], 7);
  EXPECT_EQ(data[13], 1);  // ground
  EXPECT_EQ(data[16 + 12], 255);
  std::memcpy(&x, &data[32], 4);
  EXPECT_EQ(x, 4.0f);
  EXPECT_EQ(data[32 + 13], 0);  // not ground

  CloudOptions few;
  few.max_points = 2;  // every 3rd point of each set: ground[0], objects[0]
  j = json::parse(point_cloud(3.0, origin, ground, objects, few));
  const auto small = unbase64(j["data"]);
  ASSERT_EQ(small.size(), 2u * 16u);
  std::memcpy(&x, &small[16], 4);
  EXPECT_EQ(x, 4.0f);
}

TEST(Channels, VehicleStateInSiUnits) {
  VehicleState s;
  s.stamp = 1.9999999999;  // rounds up into the next second
  s.vx = 3;
  s.vy = 4;
  s.yaw_rate = 0.5;
  s.ay = 2.25;
  s.steering = -0.1;
  const auto j = json::parse(vehicle_state_json(s, 6.0));
  EXPECT_EQ(j["timestamp"], (json{{"sec", 2}, {"nsec", 0}}));
  EXPECT_DOUBLE_EQ(j["speed"].get<double>(), 5.0);
  EXPECT_NEAR(j["sideslip"].get<double>(), std::atan2(4.0, 3.0), 1e-12);
  EXPECT_DOUBLE_EQ(j["lateral_acceleration"].get<double>(), 2.25);
  EXPECT_DOUBLE_EQ(j["yaw_rate"].get<double>(), 0.5);
  EXPECT_DOUBLE_EQ(j["steering"].get<double>(), -0.1);
  EXPECT_DOUBLE_EQ(j["target_speed"].get<double>(), 6.0);
}

TEST(Channels, StatusFaultsLogAndImageAnnotations) {
  AsStatusView v;
  v.as_state = AsState::Driving;
  v.mission = Mission::Trackdrive;
  v.lap = 1;
  v.lap_times = {52.3};
  auto j = json::parse(as_status_json(5, v));
  EXPECT_EQ(j["as_state"], "Driving");
  EXPECT_EQ(j["mission"], "trackdrive");
  EXPECT_EQ(j["lap_times"], json::array({52.3}));

  std::vector<FaultEvent> faults;
  for (int i = 0; i < 60; ++i) faults.push_back({double(i), "gnss", "fix lost " + std::to_string(i), "fallback", true});
  j = json::parse(faults_json(60, faults, 50));
  ASSERT_EQ(j["faults"].size(), 50u);
  EXPECT_EQ(j["faults"][49]["what"], "fix lost 59");
  EXPECT_EQ(j["faults"][0]["what"], "fix lost 10");

  j = json::parse(log_json(1, LogLevel::Warning, "vcu", "heartbeat late"));
  EXPECT_EQ(j["level"], 3);
  EXPECT_EQ(j["name"], "vcu");

  j = json::parse(image_annotations(1, {ImageBox{10, 20, 30, 40, ConeColour::Blue, "blue 0.9"}}));
  ASSERT_EQ(j["points"].size(), 1u);
  EXPECT_EQ(j["points"][0]["type"], 2);  // LINE_LOOP
  EXPECT_EQ(j["points"][0]["points"][2], (json{{"x", 40.0}, {"y", 60.0}}));
  EXPECT_EQ(j["texts"][0]["text"], "blue 0.9");

  const std::vector<std::uint8_t> jpeg{0xff, 0xd8, 0xff};
  j = json::parse(compressed_image(1, jpeg, "jpeg"));
  EXPECT_EQ(j["data"], "/9j/");
  EXPECT_EQ(j["format"], "jpeg");
}

TEST(Channels, TruthConesStandAsGhostsAndKnockedOnesLieApart) {
  TruthCone up;  // small blue cone standing at (3, 4) on flat ground
  up.base.translation() = Vec3(3, 4, 0);
  up.colour = ConeColour::Blue;
  up.base_width = 0.228;
  up.top_width = 0.0456;
  up.height = 0.325;
  TruthCone down = up;  // lying with its axis horizontal along +x: a rotation of 90° about y
  down.knocked = true;
  down.base = Pose3::Identity();
  down.base.linear() = Eigen::AngleAxisd(std::numbers::pi / 2, Vec3::UnitY()).toRotationMatrix();
  down.base.translation() = Vec3(1, 2, 0.1);
  const auto j = json::parse(truth_cones_scene(2.5, {up, down}));
  ASSERT_EQ(j["entities"].size(), 2u);
  const auto& standing = j["entities"][0];
  const auto& knocked = j["entities"][1];
  EXPECT_EQ(standing["id"], "truth_cones");
  EXPECT_EQ(knocked["id"], "truth_knocked_cones");
  ASSERT_EQ(standing["cylinders"].size(), 1u);
  ASSERT_EQ(knocked["cylinders"].size(), 1u);
  auto meta = [](const json& e, const std::string& key) {
    for (const auto& kv : e["metadata"])
      if (kv["key"] == key) return kv["value"].get<std::string>();
    return std::string();
  };
  EXPECT_EQ(meta(standing, "source"), "simulator ground truth");
  EXPECT_EQ(meta(knocked, "source"), "simulator ground truth");
  EXPECT_EQ(meta(standing, "render"), "ghost");
  EXPECT_EQ(meta(knocked, "render"), "");  // solid: a fallen cone must stand out
  EXPECT_EQ(meta(knocked, "count"), "1");

  const auto& a = standing["cylinders"][0];  // centre half the height above the base
  EXPECT_NEAR(a["pose"]["position"]["x"].get<double>(), 3.0, 1e-12);
  EXPECT_NEAR(a["pose"]["position"]["y"].get<double>(), 4.0, 1e-12);
  EXPECT_NEAR(a["pose"]["position"]["z"].get<double>(), 0.1625, 1e-12);
  EXPECT_NEAR(a["top_scale"].get<double>(), 0.2, 1e-12);
  EXPECT_NEAR(a["color"]["b"].get<double>(), 0.95, 1e-12);
  EXPECT_LT(a["color"]["a"].get<double>(), 0.5);

  const auto& b = knocked["cylinders"][0];  // centre half the height along +x from the base
  EXPECT_NEAR(b["pose"]["position"]["x"].get<double>(), 1.1625, 1e-12);
  EXPECT_NEAR(b["pose"]["position"]["y"].get<double>(), 2.0, 1e-12);
  EXPECT_NEAR(b["pose"]["position"]["z"].get<double>(), 0.1, 1e-12);
  EXPECT_NEAR(b["pose"]["orientation"]["y"].get<double>(), std::sin(std::numbers::pi / 4), 1e-12);
  EXPECT_NEAR(b["pose"]["orientation"]["w"].get<double>(), std::cos(std::numbers::pi / 4), 1e-12);
  EXPECT_DOUBLE_EQ(b["color"]["a"].get<double>(), 1.0);
  EXPECT_DOUBLE_EQ(b["color"]["g"].get<double>(), 0.1);  // magenta, whatever the cone's colour
}

TEST(Channels, TruthCarIsTheFootprintAndHeading) {
  CarShape shape;  // 2.9 m × 1.4 m, 0.6 m behind the rear axle
  const auto j = json::parse(truth_car_scene(0, Pose2{10, 5, std::numbers::pi / 2}, shape));
  const auto& e = j["entities"][0];
  EXPECT_EQ(e["id"], "truth_car");
  ASSERT_EQ(e["lines"].size(), 1u);
  EXPECT_EQ(e["lines"][0]["type"], 1);  // LINE_LOOP
  const auto& pts = e["lines"][0]["points"];
  ASSERT_EQ(pts.size(), 4u);
  // Heading +y: body (x, y) → map (10 − y, 5 + x).
  const double expect[4][2] = {{10.7, 4.4}, {10.7, 7.3}, {9.3, 7.3}, {9.3, 4.4}};
  for (int i = 0; i < 4; ++i) {
    EXPECT_NEAR(pts[i]["x"].get<double>(), expect[i][0], 1e-9) << i;
    EXPECT_NEAR(pts[i]["y"].get<double>(), expect[i][1], 1e-9) << i;
  }
  EXPECT_NEAR(e["arrows"][0]["pose"]["position"]["x"].get<double>(), 10.0, 1e-12);
  EXPECT_NEAR(e["arrows"][0]["pose"]["orientation"]["z"].get<double>(), std::sin(std::numbers::pi / 4), 1e-4);
}

TEST(Channels, TruthStateIsLabelledAndInSiUnits) {
  TruthState s;
  s.t = 3.25;
  s.pose = Pose2{1, 2, 0.5};
  s.speed = 10;
  s.vx = 9.9;
  s.vy = -0.3;
  s.yaw_rate = 0.4;
  s.ay = 4.1;
  s.sideslip = -0.03;
  s.cones_hit = 2;
  const auto j = json::parse(truth_state_json(s));
  EXPECT_EQ(j["source"], "simulator ground truth");
  EXPECT_EQ(j["timestamp"]["sec"], 3);
  EXPECT_EQ(j["timestamp"]["nsec"], 250000000);
  EXPECT_DOUBLE_EQ(j["speed"].get<double>(), 10);
  EXPECT_DOUBLE_EQ(j["lateral_acceleration"].get<double>(), 4.1);
  EXPECT_DOUBLE_EQ(j["sideslip"].get<double>(), -0.03);
  EXPECT_EQ(j["cones_hit"], 2);
  const auto spec = channel_spec(topics::kTruthVehicleState, Schema::TruthVehicleState, "truth");
  EXPECT_EQ(spec.schema_name, "fsd.TruthVehicleState");
  EXPECT_EQ(json::parse(spec.schema)["title"], spec.schema_name);
  // Every property the builder writes is in the schema (Foxglove Studio lists fields from it).
  const auto props = json::parse(spec.schema)["properties"];
  for (const auto& [key, value] : j.items()) EXPECT_TRUE(props.contains(key)) << key;
}

// Verified by the camera (stage Camera, or the truth source's ideal detector): a solid box; LiDAR alone: the box's
// outline. Both in the cone's colour, placed in the map by the car's pose (hand-computed).
TEST(Channels, DetectionsAreSolidWhenTheCameraVerifiedThemAndOutlinedWhenNotInTheirColour) {
  ConeDetections d;
  Cone verified = fsd::test::cone_at(2, 0, ConeColour::Blue);
  verified.stage = DetectionStage::Camera;
  Cone lidar_yellow = fsd::test::cone_at(1, 1, ConeColour::Yellow);
  lidar_yellow.stage = DetectionStage::Lidar;
  Cone lidar_unknown = fsd::test::cone_at(3, -1, ConeColour::Unknown);
  lidar_unknown.stage = DetectionStage::Lidar;
  d.cones = {verified, lidar_yellow, lidar_unknown};
  const auto j = json::parse(detections_scene(1.0, d, Pose2{10, 5, std::numbers::pi / 2}));
  ASSERT_EQ(j["entities"].size(), 2u);
  const auto& solid = j["entities"][0];
  const auto& hollow = j["entities"][1];
  EXPECT_EQ(solid["id"], "detections");
  EXPECT_EQ(hollow["id"], "detections_unverified");
  EXPECT_EQ(hollow["lifetime"], (json{{"sec", 0}, {"nsec", 500000000}}));
  ASSERT_EQ(solid["cubes"].size(), 1u);
  EXPECT_TRUE(solid["lines"].empty());
  EXPECT_NEAR(solid["cubes"][0]["pose"]["position"]["x"].get<double>(), 10.0, 1e-9);
  EXPECT_NEAR(solid["cubes"][0]["pose"]["position"]["y"].get<double>(), 7.0, 1e-9);
  EXPECT_EQ(solid["cubes"][0]["color"]["b"], 0.95);  // blue
  EXPECT_GE(solid["cubes"][0]["color"]["a"].get<double>(), 0.8);  // solid, not a ghost
  // The LiDAR-only ones: the same boxes, half transparent, with render = outline for the dashboard.
  EXPECT_EQ(hollow["metadata"], (json::array({{{"key", "render"}, {"value", "outline"}}})));
  ASSERT_EQ(hollow["cubes"].size(), 2u);
  EXPECT_TRUE(hollow["lines"].empty());
  const auto& y = hollow["cubes"][0];
  EXPECT_NEAR(y["pose"]["position"]["x"].get<double>(), 9.0, 1e-9);  // 1 m ahead, 1 m left: (10 − 1, 5 + 1)
  EXPECT_NEAR(y["pose"]["position"]["y"].get<double>(), 6.0, 1e-9);
  EXPECT_EQ(y["color"], (json{{"r", 1.0}, {"g", 0.85}, {"b", 0.05}, {"a", 0.5}}));  // yellow
  EXPECT_EQ(y["size"], solid["cubes"][0]["size"]);
  EXPECT_NEAR(hollow["cubes"][1]["pose"]["position"]["x"].get<double>(), 11.0, 1e-9);  // 3 ahead, 1 right
  EXPECT_NEAR(hollow["cubes"][1]["pose"]["position"]["y"].get<double>(), 8.0, 1e-9);
  EXPECT_EQ(hollow["cubes"][1]["color"]["r"], hollow["cubes"][1]["color"]["b"]);  // unknown: grey
  EXPECT_TRUE(camera_verified(verified));
  EXPECT_FALSE(camera_verified(lidar_yellow));
}

TEST(Channels, LocalizationGivesTheOneSigmaBoundOfTheWorstDirection) {
  LocalizationView v;
  v.t = 2.5;
  v.source = "fused";
  v.quality = "good";
  v.gnss = "accepted";
  v.has_covariance = true;
  // Position block [[0.05, 0.03], [0.03, 0.05]]: eigenvalues 0.08 and 0.02 (by hand), so 1σ = √0.08 m.
  v.covariance << 0.05, 0.03, 0, 0.03, 0.05, 0, 0, 0, 0.0004;
  const auto j = json::parse(localization_json(v));
  EXPECT_NEAR(j["position_sigma"].get<double>(), std::sqrt(0.08), 1e-12);
  EXPECT_NEAR(j["sigma_x"].get<double>(), std::sqrt(0.05), 1e-12);
  EXPECT_NEAR(j["sigma_yaw"].get<double>(), 0.02, 1e-12);
  EXPECT_EQ(j["covariance"].size(), 9u);
  EXPECT_EQ(j["source"], "fused");
  EXPECT_EQ(j["quality"], "good");
  EXPECT_EQ(j["timestamp"], (json{{"sec", 2}, {"nsec", 500000000}}));
  v.has_covariance = false;  // the truth or LiDAR-odometry source: no covariance, said so
  EXPECT_TRUE(json::parse(localization_json(v))["position_sigma"].is_null());
  v.has_covariance = true;
  v.covariance(0, 0) = std::nan("");
  EXPECT_TRUE(json::parse(localization_json(v))["position_sigma"].is_null());
}

TEST(Channels, LocalizationErrorCarriesTheEstimateToTheTruthsInstant) {
  VehicleState est;
  est.stamp = 1.0;
  est.pose = {0, 0, 0};
  est.vx = 10;
  TruthState truth;
  truth.t = 1.01;  // 10 ms later: the estimate moves 0.1 m ahead
  truth.pose = {0.1, 0.05, 0.01};
  const auto e = localization_error(est, truth);
  EXPECT_NEAR(e.dx, 0.0, 1e-12);
  EXPECT_NEAR(e.dy, -0.05, 1e-12);
  EXPECT_NEAR(e.position, 0.05, 1e-12);
  EXPECT_NEAR(e.along, -0.05 * std::sin(0.01), 1e-12);
  EXPECT_NEAR(e.across, -0.05 * std::cos(0.01), 1e-12);
  EXPECT_NEAR(e.yaw, -0.01, 1e-12);
  EXPECT_NEAR(e.carried, 0.01, 1e-12);
  truth.pose.yaw = 2 * std::numbers::pi - 0.01;  // wrapped: −0.01 rad is 0.01 rad away, not 6.27
  EXPECT_NEAR(localization_error(est, truth).yaw, 0.01, 1e-9);
  const auto j = json::parse(localization_error_json(e));
  EXPECT_NEAR(j["position_error"].get<double>(), 0.05, 1e-12);
  EXPECT_EQ(j["source"], "estimate against the simulator ground truth");
}

TEST(Channels, LoopClosuresListEachWithItsShift) {
  const std::vector<LoopClosureEvent> events = {{.t = 52.3, .lap = 1, .x = 1, .y = 2, .dx = 0.3, .dy = -0.4,
                                                 .dyaw = 0.01, .pairs = 9, .rms = 0.05, .cones_merged = 3}};
  const auto j = json::parse(loop_closures_json(60, events));
  ASSERT_EQ(j["loop_closures"].size(), 1u);
  const auto& c = j["loop_closures"][0];
  EXPECT_NEAR(c["shift"].get<double>(), 0.5, 1e-12);
  EXPECT_EQ(c["t"], 52.3);
  EXPECT_EQ(c["lap"], 1);
  EXPECT_EQ(c["pairs"], 9);
  EXPECT_TRUE(json::parse(loop_closures_json(1, {}))["loop_closures"].empty());
}

TEST(Channels, TheTruePathIsAWhiteTrailInPieces) {
  std::vector<Vec2> path;
  for (int i = 0; i < 150; ++i) path.emplace_back(1.0 * i, 2.0);
  const auto e = truth_path_entities(0, path);
  ASSERT_EQ(e.size(), 2u);
  EXPECT_EQ(e[0]["id"], "truth_path/0");
  EXPECT_EQ(e[1]["lines"][0]["points"].back()["x"].get<double>(), 149.0);
  EXPECT_EQ(e[0]["lines"][0]["color"], (json{{"r", 0.96}, {"g", 0.96}, {"b", 0.96}, {"a", 1.0}}));
  EXPECT_TRUE(truth_path_entities(0, {}).empty());
}

}  // namespace
}  // namespace fsd::web
