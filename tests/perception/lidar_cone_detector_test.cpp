// The chained LiDAR stages on a hand-made scene swept from the virtual car's mount: cones come out where they
// stand (vehicle frame), one candidate per detection, with LiDAR stage marks, range-dependent confidence and
// covariance, the striped cones' colours from the reflectivity, and distractors rejected; every point is
// accounted for by one stage.
#include <gtest/gtest.h>

#include <cmath>

#include "common/rotation.hpp"
#include "perception/lidar_cone_detector.hpp"
#include "tests/perception/ray_scene.hpp"

namespace fsd {
namespace {

using test::RayScene;
using test::SceneObject;

const Pose3 kMount = pose_zyx(Vec3(2.0, 0.0, 0.35), 0, 0, 0);

// FSG paint as the virtual car models it (drivers/sim/world/cone_geometry.cpp): blue 22 with a white stripe 95, yellow
// 70 with a black stripe 8, stripe over 0.38-0.62 of the height.
SceneObject painted(SceneObject o, double body, double stripe) {
  o.reflectivity = body, o.stripe_reflectivity = stripe, o.stripe_low = 0.38, o.stripe_high = 0.62;
  return o;
}

struct Placed {
  Vec2 at;
  ConeColour colour;
};

// Three sweeps 0.1 s apart, each from where the body (`body(t)`, scene frame) is then; the detector is told the
// poses `pose_at`. The last sweep's detection.
template <class BodyAt>
LidarDetection drive_by(LidarConeDetector& det, const RayScene& scene, const BodyAt& body, const BodyPoseAt& pose_at) {
  LidarDetection d;
  for (int k = 0; k < 3; ++k) {
    Scan s = scene.sweep_moving([&](double t) { return body(0.1 * k + t) * kMount; });
    for (auto& p : s.points) p.t += 0.1 * k;
    d = det.detect(s, pose_at);
  }
  return d;
}

TEST(LidarConeDetector, FindsTheConesOfAHandMadeSceneAndNothingElse) {
  RayScene scene;
  scene.range_noise = 0.01;
  std::vector<Placed> cones;
  for (int i = 0; i < 6; ++i) {
    const double x = 3.0 + 2.5 * i;
    cones.push_back({Vec2(x, 1.6), ConeColour::Blue});
    cones.push_back({Vec2(x, -1.6), ConeColour::Yellow});
  }
  for (const auto& c : cones)
    scene.objects.push_back(c.colour == ConeColour::Blue ? painted(test::small_cone_at(c.at.x(), c.at.y()), 22, 95)
                                                         : painted(test::small_cone_at(c.at.x(), c.at.y()), 70, 8));
  scene.objects.push_back(test::cylinder_at(6.0, 5.0, 0.3, 0.2));     // lying tyre
  scene.objects.push_back(test::cylinder_at(9.0, -5.0, 0.05, 1.3));   // post
  scene.objects.push_back(test::wall_at(-6.0, 8.0, 0.0, 12.0, 1.5));  // fence
  const Scan scan = scene.sweep(kMount, 60.0);

  LidarConeDetector det({}, kMount);
  const LidarDetection d = det.detect(scan);
  ASSERT_EQ(d.candidates.size(), d.detections.cones.size());
  EXPECT_TRUE(d.ground.valid);
  EXPECT_NEAR(d.ground.h, 0.0, 0.01);
  EXPECT_EQ(d.frames, 1);

  // Each true cone found once, within 4 cm; nothing else.
  ASSERT_EQ(d.detections.cones.size(), cones.size());
  for (const auto& truth : cones) {
    const Cone* best = nullptr;
    for (const auto& c : d.detections.cones)
      if (!best || (c.position.head<2>() - truth.at).norm() < (best->position.head<2>() - truth.at).norm()) best = &c;
    ASSERT_NE(best, nullptr);
    EXPECT_LT((best->position.head<2>() - truth.at).norm(), 0.04) << truth.at.transpose();
    EXPECT_EQ(best->stage, DetectionStage::Lidar);
    EXPECT_GT(best->points, 0u);
    const double range = (truth.at - kMount.translation().head<2>()).norm();
    if (range <= 6.0) {
      EXPECT_EQ(best->colour, truth.colour) << truth.at.transpose();
      EXPECT_EQ(best->colour_source, ColourSource::LidarIntensity);
    } else if (best->colour == ConeColour::Unknown) {
      EXPECT_EQ(best->colour_source, ColourSource::None);
    }
    if (best->colour != ConeColour::Unknown) {
      EXPECT_EQ(best->colour, truth.colour);  // never a wrong colour
    }
  }
  // Confidence and uncertainty grow with range.
  const auto by_range = [&](double r) {
    const Cone* best = nullptr;
    for (const auto& c : d.detections.cones)
      if (!best || std::abs(c.position.x() - 2.0 - r) < std::abs(best->position.x() - 2.0 - r)) best = &c;
    return *best;
  };
  const Cone near = by_range(1.0), far = by_range(13.5);
  EXPECT_GT(near.confidence, far.confidence);
  EXPECT_LT(near.covariance.trace(), far.covariance.trace());

  // Every point is in exactly one stage's count.
  const auto& n = d.counters;
  EXPECT_EQ(n.input, scan.points.size());
  EXPECT_EQ(n.invalid + n.outside_roi + n.in_body + n.ground + n.below_ground + n.above_roi + n.obstacles, n.input);
  EXPECT_EQ(n.cones, cones.size());
  EXPECT_EQ(d.rejected.size(), n.clusters - n.cones);
  // The distractors were seen and rejected: the post as too tall, the fence as too wide, the lying tyre (which
  // the lasers cross only at its foot from there) as lower than any cone.
  const auto rejected_near = [&](const Vec2& p, double within) {
    for (const auto& r : d.rejected)
      if ((r.position.head<2>() - p).norm() < within) return r.reason;
    return ConeRejection::None;
  };
  EXPECT_EQ(rejected_near(Vec2(9.0, -5.0), 0.3), ConeRejection::TooTall);
  EXPECT_EQ(rejected_near(Vec2(0.0, 8.0), 6.0), ConeRejection::TooWide);
  EXPECT_EQ(rejected_near(Vec2(6.0, 5.0), 0.4), ConeRejection::TooFlat);
}

TEST(LidarConeDetector, DropsNonFiniteAndEmptyInput) {
  LidarConeDetector det({}, kMount);
  const LidarDetection empty = det.detect(Scan{});
  EXPECT_TRUE(empty.detections.cones.empty());
  EXPECT_TRUE(empty.counters.ground_fallback);
  Scan bad;
  bad.points.resize(10);
  for (auto& p : bad.points) p.x = std::nanf("");
  const LidarDetection d = det.detect(bad);
  EXPECT_EQ(d.counters.invalid, 10u);
  EXPECT_TRUE(d.detections.cones.empty());
}

TEST(LidarConeDetector, AccumulatesOnlyWithKnownMotion) {
  RayScene scene;
  scene.objects.push_back(test::small_cone_at(9.0, 0.5));
  LidarDetectorConfig cfg;
  LidarConeDetector det(cfg, kMount);
  // The car creeps forward at 5 m/s: three sweeps 0.1 s apart, each taken from where the car is then.
  const auto body = [](Stamp t) { return pose_zyx(Vec3(5.0 * t, 0, 0), 0, 0, 0); };
  const BodyPoseAt pose_at = body;
  const LidarDetection d = drive_by(det, scene, body, pose_at);
  EXPECT_EQ(d.frames, 3);
  ASSERT_EQ(d.detections.cones.size(), 1u);
  // The cone's true place in the body frame at the last firing (t ≈ 0.3 s).
  const Vec3 truth = body(d.detections.stamp).inverse() * Vec3(9.0, 0.5, 0.0);
  EXPECT_LT((d.detections.cones[0].position - truth).head<2>().norm(), 0.04);
  // Without poses nothing is accumulated.
  LidarConeDetector still(cfg, kMount);
  EXPECT_EQ(still.detect(scene.sweep(kMount)).frames, 1);
}

// A car cornering on its springs: rolled 0.34° (0.65 g) and pitching 0.6°/s as it brakes, while it yaws at
// 0.8 rad/s; its poses planar as the odometry gives them. The earlier frames' returns of a cone 15 m out must lie where the cone is, by each frame's
// ground: moved by the planar poses alone, the roll turned with the yaw puts them centimetres off in height, which
// is what the far colour reads (a laser's height on the cone tells the body from the stripe).
TEST(LidarConeDetector, AccumulatesACorneringCarsFramesOnTheirOwnGround) {
  const auto planar = [](Stamp t) {
    const double yaw = 0.8 * t;
    return pose_zyx(Vec3(10.0 * std::sin(yaw), 10.0 * (1 - std::cos(yaw)), 0.0), yaw, 0, 0);
  };
  const auto body = [&](Stamp t) { return planar(t) * pose_zyx(Vec3::Zero(), 0.0, 0.002 + 0.01 * t, 0.006); };
  // The cone 14 m ahead-left of the LiDAR at the last sweep, in every sweep's view.
  const Vec3 cone = planar(0.3) * Vec3(13.0, 8.5, 0.0);
  RayScene scene;
  scene.objects.push_back(painted(test::small_cone_at(cone.x(), cone.y()), 22, 95));
  const auto& shape = scene.objects.back();
  LidarConeDetector det({}, kMount);
  const BodyPoseAt pose_at = planar;  // what the localization knows
  const LidarDetection d = drive_by(det, scene, body, pose_at);
  ASSERT_EQ(d.frames, 3);
  // Each accumulated return near the cone, moved by the true body pose, lies on the cone's surface.
  const Pose3 now = body(d.detections.stamp);
  int on_cone = 0;
  double worst = 0;
  for (const auto& q : d.obstacle_points) {
    const Vec3 w = now * Vec3(q.x, q.y, q.z);
    const double radial = (w - cone).head<2>().norm();
    if (radial > 0.4) continue;
    ++on_cone;
    // Off the frustum's surface, measured along the height (the side is steep: a height error shows as a radius).
    const double r_at = shape.r0 - (shape.r0 - shape.r1) * w.z() / shape.h;
    const double height_error = (radial - r_at) * shape.h / (shape.r0 - shape.r1);
    worst = std::max(worst, std::abs(height_error));
  }
  EXPECT_GE(on_cone, 8);
  EXPECT_LT(worst, 0.01);  // 4 cm by the planar poses alone
}

}  // namespace
}  // namespace fsd
