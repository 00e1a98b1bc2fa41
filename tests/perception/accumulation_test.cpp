// Motion compensation and accumulation against a static scene of known points: a scan taken while the car drives
// and turns comes back to the scene as seen at the reference time, and the last m frames moved by their poses
// lie on the same scene points (paper eq. 6-8).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "common/rotation.hpp"
#include "perception/frame_accumulator.hpp"
#include "perception/scan_motion.hpp"

namespace fsd {
namespace {

// The car at time t: 10 m/s forward while yawing at 0.8 rad/s, with a little pitch oscillation.
Pose3 drive(Stamp t) {
  const double yaw = 0.8 * t;
  const double x = 10.0 * std::sin(yaw) / 0.8, y = 10.0 * (1 - std::cos(yaw)) / 0.8;
  return pose_zyx(Vec3(x, y, 0.0), yaw, 0.01 * std::sin(20 * t), 0.0);
}

const Pose3 kMount = pose_zyx(Vec3(2.0, 0.1, 0.35), 0.02, 0.01, 0.0);  // body ← sensor

// Static scene points (map frame) and the sensor-frame points a moving sensor measures of them at times t.
struct Observed {
  std::vector<Vec3> map;
  std::vector<Point> sensor;
};
Observed observe(double t0, double t1, int n) {
  Observed o;
  for (int i = 0; i < n; ++i) {
    const double t = t0 + (t1 - t0) * i / (n - 1);
    const double a = 2 * 3.14159265358979 * i / n;
    const Vec3 p = drive(t) * Vec3(2.0 + 9.0 * std::cos(a), 7.0 * std::sin(a), 0.1 + 0.01 * (i % 30));
    o.map.push_back(p);
    const Vec3 s = (drive(t) * kMount).inverse() * p;
    Point q;
    q.x = static_cast<float>(s.x()), q.y = static_cast<float>(s.y()), q.z = static_cast<float>(s.z());
    q.t = t;
    o.sensor.push_back(q);
  }
  return o;
}

TEST(ScanMotion, DeskewsAScanTakenWhileDrivingAndTurning) {
  const double t0 = 5.0, t1 = 5.1;
  const Observed o = observe(t0, t1, 2000);
  const BodyPoseAt pose_at = [](Stamp t) { return drive(t); };
  const ScanMotion motion(kMount, t0, t1, t1, pose_at, 10);
  EXPECT_TRUE(motion.has_motion());
  const Pose3 ref_inv = drive(t1).inverse();
  double worst = 0, worst_static = 0;
  const ScanMotion standing(kMount, t0, t1, t1, {}, 10);  // no motion known: body ← sensor only
  for (std::size_t i = 0; i < o.map.size(); ++i) {
    const Vec3 truth = ref_inv * o.map[i];  // the point in the body frame at t1
    const auto& q = o.sensor[i];
    const Eigen::Vector3f p(q.x, q.y, q.z);
    worst = std::max(worst, (motion.to_reference(p, q.t).cast<double>() - truth).norm());
    worst_static = std::max(worst_static, (standing.to_reference(p, q.t).cast<double>() - truth).norm());
  }
  EXPECT_LT(worst, 0.002);       // float points 10 m out; first-order interpolation between knots
  EXPECT_GT(worst_static, 0.5);  // without deskew the first firings are a metre off
}

TEST(ScanMotion, InterpolatesTwoStampedPoses) {
  const Pose3 a = pose_zyx(Vec3(0, 0, 0), 0.0, 0, 0), b = pose_zyx(Vec3(1.0, 0.2, 0), 0.1, 0, 0);
  const BodyPoseAt f = interpolate_poses(1.0, a, 2.0, b);
  const Pose3 mid = f(1.5);
  EXPECT_TRUE(mid.translation().isApprox(Vec3(0.5, 0.1, 0), 1e-12));
  EXPECT_NEAR(to_pose2(mid).yaw, 0.05, 1e-12);
  EXPECT_TRUE(f(0.0).isApprox(a));  // held outside the interval
  EXPECT_TRUE(f(3.0).isApprox(b));
}

TEST(FrameAccumulator, FramesMovedByTheirPosesReproduceTheStaticScene) {
  AccumulationConfig cfg;
  cfg.frames = 3;
  FrameAccumulator acc(cfg);
  const std::vector<Vec3> scene{{8, 2, 0.2}, {12, -3, 0.1}, {6, 5, 0.3}, {20, 0, 0.15}};
  std::vector<Pose3> poses;
  for (int k = 0; k < 5; ++k) {
    poses.push_back(drive(0.1 * k));
    std::vector<Point> frame;
    for (const auto& p : scene) {
      const Vec3 b = poses.back().inverse() * p;  // the scene in this frame's body frame
      Point q;
      q.x = static_cast<float>(b.x()), q.y = static_cast<float>(b.y()), q.z = static_cast<float>(b.z());
      q.ring = static_cast<std::uint16_t>(k);  // which frame it came from
      frame.push_back(q);
    }
    acc.add(frame, poses.back());
  }
  EXPECT_EQ(acc.frames(), 3u);  // bounded: the last m frames
  std::vector<Point> out;
  acc.collect(out);
  ASSERT_EQ(out.size(), 3 * scene.size());
  const Pose3 now_inv = poses.back().inverse();
  for (std::size_t i = 0; i < out.size(); ++i) {
    EXPECT_GE(out[i].ring, 2);  // frames 2, 3, 4 kept
    const Vec3 truth = now_inv * scene[i % scene.size()];
    EXPECT_LT((Vec3(out[i].x, out[i].y, out[i].z) - truth).norm(), 1e-4) << i;
  }
}

TEST(FrameAccumulator, BoundsThePointsKeptPerFrame) {
  AccumulationConfig cfg;
  cfg.frames = 2;
  cfg.max_points_per_frame = 100;
  FrameAccumulator acc(cfg);
  std::vector<Point> big(1000);
  for (std::size_t i = 0; i < big.size(); ++i) big[i].x = static_cast<float>(i);
  EXPECT_EQ(acc.add(big, Pose3::Identity()), 900u);
  std::vector<Point> out;
  acc.collect(out);
  ASSERT_EQ(out.size(), 100u);
  EXPECT_FLOAT_EQ(out.front().x, 0.0f);  // an even subsample over the whole frame
  EXPECT_GE(out.back().x, 980.0f);
}

}  // namespace
}  // namespace fsd
