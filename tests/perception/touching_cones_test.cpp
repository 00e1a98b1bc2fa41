// Touching cones on a hand-made scene (the simulator's ray casting, a VLP-16 from the virtual car's mount): groups
// of two and three cones whose bases stand 3 to 15 cm apart, across, along and diagonal to the line of sight, at
// 3 to 14 m. Each cluster is too wide for one cone; each cone must come out once, where it stands, and the
// distractors that are also too wide (a tyre stack, a lying tyre, a low wall, a pair of bollards) must not.
#include <gtest/gtest.h>

#include <cmath>

#include "common/rotation.hpp"
#include "perception/lidar_cone_detector.hpp"
#include "perception/touching_cones.hpp"
#include "tests/perception/ray_scene.hpp"

namespace fsd {
namespace {

using test::RayScene;
using test::SceneObject;

const Pose3 kMount = pose_zyx(Vec3(2.0, 0.0, 0.35), 0, 0, 0);

SceneObject blue_cone(const Vec2& at) {
  SceneObject o = test::small_cone_at(at.x(), at.y());
  o.reflectivity = 22, o.stripe_reflectivity = 95, o.stripe_low = 0.38, o.stripe_high = 0.62;
  return o;
}

// `count` cones in a row from the sensor's point of view at `range` and `bearing` (rad), the row turned `across`
// (rad) from the line of sight, their centres `spacing` apart.
std::vector<Vec2> row(double range, double bearing, double across, int count, double spacing) {
  const Vec2 sensor = kMount.translation().head<2>();
  const Vec2 first = sensor + range * Vec2(std::cos(bearing), std::sin(bearing));
  const Vec2 dir(std::cos(bearing + across), std::sin(bearing + across));
  std::vector<Vec2> out;
  for (int i = 0; i < count; ++i) out.push_back(first + i * spacing * dir);
  return out;
}

const Cone* nearest(const LidarDetection& d, const Vec2& p) {
  const Cone* best = nullptr;
  for (const auto& c : d.detections.cones)
    if (!best || (c.position.head<2>() - p).norm() < (best->position.head<2>() - p).norm()) best = &c;
  return best;
}

TEST(TouchingCones, EachConeOfATouchingGroupIsFoundWhereItStands) {
  constexpr double kPi = 3.14159265358979;
  RayScene scene;
  scene.range_noise = 0.01;
  std::vector<Vec2> cones;
  // range, bearing, row angle to the line of sight, cones, centre spacing (base gap = spacing − 0.228 m)
  std::vector<Vec2> near_groups;
  for (const auto& g :
       {row(3.5, -0.7, kPi / 2, 3, 0.28), row(6.0, 0.5, kPi / 2, 2, 0.26), row(5.0, 2.6, kPi / 3, 2, 0.29)})
    near_groups.insert(near_groups.end(), g.begin(), g.end());
  for (const auto& g :
       {row(3.5, -0.7, kPi / 2, 3, 0.28), row(6.0, 0.5, kPi / 2, 2, 0.26), row(8.0, -0.2, kPi / 4, 2, 0.27),
        row(10.0, 0.15, 0.5, 2, 0.28), row(12.0, -0.45, kPi / 2, 2, 0.30), row(5.0, 2.6, kPi / 3, 2, 0.29)})
    cones.insert(cones.end(), g.begin(), g.end());
  for (const auto& c : cones) scene.objects.push_back(blue_cone(c));
  // Distractors too wide for a cone, none of them cones side by side.
  scene.objects.push_back(test::cylinder_at(-4.0, 4.0, 0.3, 0.45));   // a stack of two tyres
  scene.objects.push_back(test::cylinder_at(-4.0, 4.62, 0.3, 0.45));  // and another beside it
  scene.objects.push_back(test::cylinder_at(6.0, -6.0, 0.3, 0.2));    // a lying tyre
  scene.objects.push_back(test::wall_at(-6.0, -3.0, 0.3, 0.9, 0.3));  // a low board
  const Scan scan = scene.sweep(kMount, 60.0);

  LidarDetectorConfig off;
  off.touching.enabled = false;
  const LidarDetection before = LidarConeDetector(off, kMount).detect(scan);
  const LidarDetection d = LidarConeDetector({}, kMount).detect(scan);

  // Without the split, the near groups (bases 3-6 cm apart, across the line of sight) are one cluster each, too
  // wide for a cone: none of their cones is found. (Farther, the visible sides stand apart by more than the
  // clustering tolerance and are found either way.)
  for (std::size_t i = 0; i < 7; ++i) {
    const Cone* c = nearest(before, near_groups[i]);
    EXPECT_TRUE(c == nullptr || (c->position.head<2>() - near_groups[i]).norm() > 0.2) << near_groups[i].transpose();
  }
  EXPECT_GE(before.counters.too_wide, 3u);

  ASSERT_EQ(d.detections.cones.size(), cones.size());
  for (const auto& truth : cones) {
    const Cone* c = nearest(d, truth);
    ASSERT_NE(c, nullptr);
    EXPECT_LT((c->position.head<2>() - truth).norm(), 0.05) << truth.transpose();
  }
  EXPECT_GE(d.counters.split_clusters, 3u);
  EXPECT_EQ(d.counters.cones, cones.size());
  // Every cluster is a cone, a split group or rejected.
  EXPECT_EQ(d.rejected.size() + d.counters.split_clusters + (d.counters.cones - d.counters.split_cones),
            d.counters.clusters);
}

TEST(TouchingCones, ASingleConeAndAnObjectWithOneTopAreNotSplit) {
  RayScene scene;
  scene.range_noise = 0.01;
  const Vec2 cone(6.0, 2.0);
  scene.objects.push_back(blue_cone(cone));
  scene.objects.push_back(test::cylinder_at(8.0, -3.0, 0.3, 0.45));  // a tyre stack
  const Scan scan = scene.sweep(kMount, 60.0);
  const LidarDetection d = LidarConeDetector({}, kMount).detect(scan);
  ASSERT_EQ(d.detections.cones.size(), 1u);
  EXPECT_LT((d.detections.cones[0].position.head<2>() - cone).norm(), 0.05);
  EXPECT_EQ(d.counters.split_clusters, 0u);
}

TEST(TouchingCones, OneLaserAcrossBlackPaintIsNoEvidence) {
  // A pair of touching cones 10 m away, which only the −1° laser crosses, at 0.175 m: within the stripe. On blue
  // cones the white stripe shows paint, and the pair is split; on yellow cones the stripe is black, as a black tyre's
  // rubber whose returns thin out into pieces along one laser's arc, and the pair stays one cluster (not a cone).
  constexpr double kPi = 3.14159265358979;
  for (const bool blue : {true, false}) {
    RayScene scene;
    scene.range_noise = 0.005;
    const auto pair = row(10.0, 0.3, kPi / 2, 2, 0.27);
    for (const auto& c : pair) {
      SceneObject o = blue_cone(c);
      if (!blue) o.reflectivity = 70, o.stripe_reflectivity = 8;
      scene.objects.push_back(o);
    }
    const LidarDetection d = LidarConeDetector({}, kMount).detect(scene.sweep(kMount, 60.0));
    if (blue) {
      ASSERT_EQ(d.detections.cones.size(), 2u);
      EXPECT_EQ(d.counters.split_clusters, 1u);
      for (const auto& truth : pair) EXPECT_LT((nearest(d, truth)->position.head<2>() - truth).norm(), 0.08);
    } else {
      EXPECT_EQ(d.detections.cones.size(), 0u);
      EXPECT_EQ(d.counters.split_clusters, 0u);
      EXPECT_EQ(d.counters.too_wide + d.counters.not_cone_shaped, 1u);
    }
  }
}

// The shared real capture (a street, no cones): one laser's arc along a kerb or wall 22 m away, 17 consecutive
// firings whose returns lie 0.08-0.16 m apart (seen obliquely), wider than the upper points' tolerance there. Split by that spacing
// alone it was 7 "cones" (`fsd detect --cloud ../shared/data/vlp16/velodyne_vlp16.pcap`: 14 detections, 7 without
// the split); consecutive firings of one laser are one continuous top.
TEST(TouchingCones, ConsecutiveFiringsOfOneLaserAreOneTop) {
  struct Recorded {
    float x, y, height, azimuth;
  };
  const std::vector<Recorded> arc{
      {11.450, -19.791, 0.261, 1.0463}, {11.395, -19.851, 0.255, 1.0497}, {11.258, -19.768, 0.260, 1.0531},
      {11.155, -19.743, 0.260, 1.0565}, {11.037, -19.691, 0.263, 1.0599}, {10.946, -19.691, 0.264, 1.0634},
      {10.860, -19.698, 0.264, 1.0669}, {10.726, -19.616, 0.273, 1.0704}, {10.619, -19.584, 0.277, 1.0739},
      {10.501, -19.534, 0.283, 1.0775}, {10.392, -19.497, 0.287, 1.0811}, {10.313, -19.517, 0.287, 1.0847},
      {10.192, -19.445, 0.295, 1.0880}, {10.089, -19.413, 0.299, 1.0915}, {9.995, -19.394, 0.302, 1.0949},
      {9.885, -19.338, 0.309, 1.0982},  {9.788, -19.312, 0.313, 1.1017}};
  std::vector<Point> cloud;
  Cluster cluster;
  for (std::size_t i = 0; i < arc.size(); ++i) {
    Point q;
    q.x = arc[i].x, q.y = arc[i].y, q.z = arc[i].height;  // heights above the capture's ground: a flat ground here
    q.ring = 6;
    q.azimuth = arc[i].azimuth;
    q.t = 5.5e-5 * static_cast<double>(i);  // one firing per 0.2° at 600 rpm
    q.intensity = 10;
    cloud.push_back(q);
    cluster.indices.push_back(static_cast<std::uint32_t>(i));
  }
  const GroundSurface flat{GroundPlane{}};
  TouchingConesSplitter splitter({}, 0.2, 8.0);
  EXPECT_TRUE(splitter.split(cloud, cluster, flat, Vec2::Zero()).empty());
}

}  // namespace
}  // namespace fsd
