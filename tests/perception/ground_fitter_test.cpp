// The ground stage against planes of known tilt and height: LiDAR sweeps of a tilted ground with cones and a wall
// on it, from sensors 0.2-1 m above it and pitched up to ±5°, in the sensor's own frame (as `fsd detect` sees a
// cloud of unknown mount); the fitted a, b, h must be the generating plane's.
#include <gtest/gtest.h>

#include <cmath>

#include "common/rotation.hpp"
#include "perception/ground_fitter.hpp"
#include "perception/ground_split.hpp"
#include "tests/perception/ray_scene.hpp"

namespace fsd {
namespace {

using test::RayScene;

// The ground plane seen from a sensor at `height` above the scene origin with `pitch` and `roll`, expressed in the
// sensor frame: z = a·x + b·y + h.
struct SensorPlane {
  double a, b, h;
};
SensorPlane plane_in_sensor(const RayScene& s, const Pose3& scene_from_sensor) {
  // Ground normal and a point in the scene, moved into the sensor frame.
  const Pose3 inv = scene_from_sensor.inverse();
  const Vec3 n = inv.linear() * Vec3(-s.a, -s.b, 1.0).normalized();
  const Vec3 p = inv * Vec3(0, 0, s.h);
  return {-n.x() / n.z(), -n.y() / n.z(), p.z() + (n.x() * p.x() + n.y() * p.y()) / n.z()};
}

std::vector<Point> points_of(const Scan& s) { return s.points; }

GroundConfig sensor_frame_config(const std::string& method) {
  GroundConfig g;
  g.method = method;
  g.height_min = -3.0;  // anywhere below the sensor, as fsd detect searches
  g.height_max = -0.1;
  return g;
}

RayScene cluttered_ground(double a, double b) {
  RayScene s;
  s.a = a, s.b = b, s.h = 0.0;
  s.range_noise = 0.01;
  for (int i = 0; i < 12; ++i) {
    const double x = -10.0 + 2.0 * i, y = (i % 2 ? 2.5 : -2.5);
    s.objects.push_back(test::small_cone_at(x, y, s.a * x + s.b * y));
  }
  s.objects.push_back(test::wall_at(-8, 7, 0.1, 16, 1.5));
  return s;
}

class GroundFitterMounts : public ::testing::TestWithParam<std::string> {};

TEST_P(GroundFitterMounts, RecoversTheTiltAndHeightOfTheGroundFromEveryMount) {
  for (double height : {0.2, 0.35, 0.6, 1.0})
    for (double pitch_deg : {-5.0, 0.0, 3.0, 5.0}) {
      const double roll_deg = pitch_deg / 2;
      const RayScene scene = cluttered_ground(0.02, -0.01);  // the ground itself slopes 1.1° and 0.6°
      const Pose3 mount =
          pose_zyx(Vec3(1.0, 0.5, scene.a + 0.5 * scene.b + height), 0.3, deg2rad(pitch_deg), deg2rad(roll_deg));
      const Scan scan = scene.sweep(mount, 30.0);
      std::vector<Point> pts;
      for (const auto& p : scan.points)
        if (std::abs(p.x) < 20 && std::abs(p.y) < 20) pts.push_back(p);
      GroundFitter fitter(sensor_frame_config(GetParam()));
      const GroundPlane g = fitter.fit(pts);
      const SensorPlane truth = plane_in_sensor(scene, mount);
      SCOPED_TRACE(::testing::Message() << "height " << height << " pitch " << pitch_deg);
      ASSERT_TRUE(g.valid);
      EXPECT_NEAR(g.a, truth.a, 0.002);
      EXPECT_NEAR(g.b, truth.b, 0.002);
      EXPECT_NEAR(g.h, truth.h, 0.01);
      EXPECT_LT(g.rms, 0.02);
    }
}

INSTANTIATE_TEST_SUITE_P(Methods, GroundFitterMounts, ::testing::Values("grid_lsq", "pcl_sac"));

TEST(GroundFitter, KeepsToTheConfiguredTiltAndHeight) {
  // A steep ramp (15°) is no ground with a 8° tilt bound; nor a plane far outside the height bounds.
  RayScene ramp;
  ramp.a = std::tan(deg2rad(15.0));
  const Scan scan = ramp.sweep(pose_zyx(Vec3(0, 0, 0.5), 0, 0, 0), 20.0);
  GroundFitter fitter(sensor_frame_config("grid_lsq"));
  EXPECT_FALSE(fitter.fit(points_of(scan)).valid);
  GroundFitter pcl(sensor_frame_config("pcl_sac"));
  EXPECT_FALSE(pcl.fit(points_of(scan)).valid);

  RayScene flat;
  GroundConfig vehicle_frame;                                              // h within ±0.3 m of the frame origin
  const Scan high = flat.sweep(pose_zyx(Vec3(0, 0, 1.0), 0, 0, 0), 20.0);  // ground 1 m below the origin
  EXPECT_FALSE(GroundFitter(vehicle_frame).fit(points_of(high)).valid);
  EXPECT_FALSE(GroundFitter(vehicle_frame).fit({}).valid);
}

TEST(GroundSplit, RemovesTheGroundAndKeepsTheConesUpToTheRegionHeight) {
  RayScene scene;
  scene.objects.push_back(test::small_cone_at(5, 0));
  scene.objects.push_back(test::cylinder_at(6, 3, 0.05, 2.0));  // a post, higher than the 1 m region
  const Scan scan = scene.sweep(pose_zyx(Vec3(0, 0, 0.5), 0, 0, 0), 20.0);
  GroundPlane g;
  g.a = g.b = 0, g.h = -0.5, g.valid = true;
  std::vector<Point> ground, obstacles;
  GroundSplitter splitter;
  const auto c = splitter.split(scan.points, g, 0.05, 1.0, &ground, obstacles);
  EXPECT_EQ(c.ground + c.obstacles + c.below + c.above, scan.points.size());
  EXPECT_EQ(c.below, 0u);
  EXPECT_GT(c.above, 0u);  // the post above 1 m
  for (const auto& p : obstacles) {
    EXPECT_GE(p.z, -0.5 + 0.05);
    EXPECT_LE(p.z, -0.5 + 1.0);
  }
  // Every cone point above the band is kept.
  int cone_points = 0;
  for (const auto& p : obstacles) cone_points += std::hypot(p.x - 5, p.y) < 0.2;
  EXPECT_GT(cone_points, 10);
  for (const auto& p : ground) EXPECT_NEAR(p.z, -0.5, 0.05);
}

TEST(GroundSplit, GrazingBeamsFindAFarConeTheHeightBandHides) {
  // Sensor 0.35 m up: its −1° laser meets the ground at 20 m and crosses a cone at 18.5 m only 3 cm up, inside the
  // ±5 cm ground band. The grazing test finds it from the range gap to the laser's ground on both sides.
  RayScene scene;
  scene.objects.push_back(test::small_cone_at(18.5, 0.0));
  const Scan scan = scene.sweep(pose_zyx(Vec3(0, 0, 0.35), 0, 0, 0), 30.0);
  GroundPlane g;
  g.h = -0.35, g.valid = true;
  const auto cone_points = [](const std::vector<Point>& v) {
    int n = 0;
    for (const auto& p : v) n += std::hypot(p.x - 18.5, p.y) < 0.2;
    return n;
  };
  GroundSplitter splitter;
  std::vector<Point> plain, grazing_found;
  splitter.split(scan.points, g, 0.05, 1.0, nullptr, plain);
  EXPECT_EQ(cone_points(plain), 0);  // all within the band
  GrazingBeams beams;
  const auto c = splitter.split(scan.points, g, 0.05, 1.0, nullptr, grazing_found, &beams);
  EXPECT_GE(cone_points(grazing_found), 3);
  EXPECT_EQ(static_cast<int>(c.grazing), cone_points(grazing_found));  // nothing else: the flat ground stays ground
}

TEST(GroundSplit, GrazingBeamsLeaveAPitchedSensorsGroundAlone) {
  // Pitched 4° with a 3 % slope across: each ring's range sweeps along the azimuth, never short of both sides.
  RayScene scene;
  scene.b = 0.03;
  const Pose3 mount = pose_zyx(Vec3(0, 0, 0.35), 0, deg2rad(4.0), 0);
  const Scan scan = scene.sweep(mount, 40.0);
  const auto truth = plane_in_sensor(scene, mount);
  GroundPlane g;
  g.a = truth.a, g.b = truth.b, g.h = truth.h, g.valid = true;
  GroundSplitter splitter;
  std::vector<Point> obstacles;
  const GrazingBeams beams;
  const auto c = splitter.split(scan.points, g, 0.05, 1.0, nullptr, obstacles, &beams);
  EXPECT_EQ(c.grazing, 0u);
  EXPECT_EQ(obstacles.size(), 0u);
}

}  // namespace
}  // namespace fsd
