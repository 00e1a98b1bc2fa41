// Points decoded from the VLP-16 model's packets land on the surfaces of the world. Decoding is done here from
// the wire layout alone (vlp16_format.hpp): per-laser azimuth interpolated between blocks and firing time from the
// packet timestamp as the VLP-16 manual describes, and the ROS velodyne formula
//   x = d·cosω·cosα,  y = −d·cosω·sinα,  z = d·sinω + vertical offset
// for the sensor frame (x forward, y left, z up).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "common/wire/vlp16_format.hpp"
#include "drivers/sim/sensors/lidar_model.hpp"
#include "tests/sim/world_test_util.hpp"

namespace fsd::sim {
namespace {

namespace vlp = wire::vlp16;
using test::bare_config;
using test::make_cone;
using test::make_track;

struct Return {
  Vec3 p;    // sensor frame
  Vec3 dir;  // unit beam direction, sensor frame
  double distance;
  double azimuth_deg;
  double t;  // firing time, s past the hour
  int laser;
  int intensity;
};

std::vector<Return> decode(std::span<const std::uint8_t> pkt) {
  std::vector<Return> out;
  const double t0 = vlp::read_u32(pkt, vlp::kTimestampOffset) * 1e-6;
  for (std::size_t b = 0; b < vlp::kBlocks; ++b) {
    const double az = vlp::read_u16(pkt, b * vlp::kBlockSize + 2) * 0.01;
    const double next = b + 1 < vlp::kBlocks ? vlp::read_u16(pkt, (b + 1) * vlp::kBlockSize + 2) * 0.01
                                             : az + (az - vlp::read_u16(pkt, (b - 1) * vlp::kBlockSize + 2) * 0.01);
    const double step = std::fmod(next - az + 720.0, 360.0);
    for (std::size_t s = 0; s < 2; ++s)
      for (std::size_t k = 0; k < 16; ++k) {
        const auto at = vlp::channel_offset(b, s, k);
        const std::uint16_t counts = vlp::read_u16(pkt, at);
        if (counts == 0) continue;
        const double dt_us = b * 110.592 + s * 55.296 + k * 2.304;
        const double alpha = deg2rad(az + step * (k * 2.304 + s * 55.296) / 110.592);
        const double omega = deg2rad(vlp::kLaserTable[k].elevation_deg);
        const double d = counts * 0.002;
        const Vec3 dir(std::cos(omega) * std::cos(alpha), -std::cos(omega) * std::sin(alpha), std::sin(omega));
        Return r;
        r.dir = dir;
        r.p = d * dir + Vec3(0, 0, vlp::kLaserTable[k].vertical_offset_m);
        r.distance = d;
        r.azimuth_deg = std::fmod(rad2deg(alpha), 360.0);
        r.t = t0 + dt_us * 1e-6;
        r.laser = static_cast<int>(k);
        r.intensity = pkt[at + 2];
        out.push_back(r);
      }
  }
  return out;
}

double segment_distance(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 ab = b - a;
  const double s = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return (a + s * ab - p).norm();
}

// Distance of a map point from the surface of an upright small cone standing at (cx, cy) on flat ground: in the
// (radial, height) half-plane the cone's outline is top disc (0, h)–(r1, h), side (r1, h)–(r0, 0).
double small_cone_surface_distance(const Vec3& p, double cx, double cy) {
  const Vec2 q(std::hypot(p.x() - cx, p.y() - cy), p.z());
  return std::min(segment_distance(q, Vec2(0, 0.325), Vec2(0.025, 0.325)),
                  segment_distance(q, Vec2(0.025, 0.325), Vec2(0.114, 0.0)));
}

// Map ← sensor of the default mounting on a body at pose_xy_yaw... here the body frame is the map frame.
Pose3 mount() { return lidar_mount(LidarConfig{}); }

TEST(LidarGeometry, StaticSensorSeesTheConeSurfaceAndTheGroundWithinTheRangeNoise) {
  // Sensor at (2.0, 0, 0.35); cone 3 m ahead and 1.5 m to the left of it.
  const double cx = 5.0, cy = 1.5;
  const World world(make_track({make_cone(cx, cy)}), bare_config(), 1);
  LidarConfig cfg;  // ±3 cm
  LidarModel lidar(cfg, world, 11);
  std::vector<std::uint8_t> all;
  int cone_points = 0, ground_points = 0, stripe_sum = 0, stripe_n = 0, body_sum = 0, body_n = 0;
  double az_sum = 0, ground_sq = 0;
  lidar.advance_to(
      1.0, [](Stamp) { return Pose3::Identity(); },
      [&](Stamp, std::span<const std::uint8_t> pkt) {
        for (const auto& r : decode(pkt)) {
          const Vec3 p = mount() * r.p;
          const double to_cone = small_cone_surface_distance(p, cx, cy);
          const double to_ground = std::abs(p.z());
          // Every return lies on one of the two surfaces, within the noise bound (plus 1 mm quantisation and the
          // 0.01° azimuth resolution).
          ASSERT_LE(std::min(to_cone, to_ground), 0.03 + 0.002) << p.transpose();
          if (to_cone < to_ground && p.z() > 0.04) {
            ++cone_points;
            az_sum += r.azimuth_deg;
            const double frac = p.z() / 0.325;
            if (frac > 0.42 && frac < 0.58) stripe_sum += r.intensity, ++stripe_n;
            if (frac < 0.32 || frac > 0.68) body_sum += r.intensity, ++body_n;
          } else if (to_ground < to_cone) {
            ++ground_points;
            // Along-beam residual against the exact flat-ground distance from the beam origin (0, 0, v) + mount.
            const Vec3 origin =
                mount() * Vec3(0, 0, vlp::kLaserTable[static_cast<std::size_t>(r.laser)].vertical_offset_m);
            const Vec3 dir = mount().linear() * r.dir;
            const double exact = -origin.z() / dir.z();
            ground_sq += (r.distance - exact) * (r.distance - exact);
          }
        }
      });
  // 10 turns; the cone (23 cm wide at 3.3 m, 4° of azimuth) is crossed by three rings at 0.2° steps.
  EXPECT_GT(cone_points, 250);
  EXPECT_GT(ground_points, 100000);
  // Clockwise azimuth from +x: a cone ahead and to the left is at 360° − atan2(1.5, 3.0) = 333.43°.
  EXPECT_NEAR(az_sum / cone_points, 333.43, 0.5);
  // Range noise σ = 1.5 cm truncated at 3 cm has a standard deviation of 0.88σ = 1.32 cm.
  EXPECT_NEAR(std::sqrt(ground_sq / ground_points), 0.0132, 0.0015);
  // The white stripe of a blue cone is brighter than its body.
  ASSERT_GT(stripe_n, 10);
  ASSERT_GT(body_n, 10);
  EXPECT_GT(static_cast<double>(stripe_sum) / stripe_n, 2.0 * body_sum / body_n);
}

TEST(LidarGeometry, GroundReturnsLieOnTheSlopedPlane) {
  WorldConfig wc = bare_config();
  wc.ground_slope_x = 0.03;
  wc.ground_slope_y = -0.02;
  const World world(make_track({}), wc, 1);
  LidarConfig cfg;
  cfg.range_noise = 0.0;
  LidarModel lidar(cfg, world, 1);
  // The car stands on the slope at (10, 5), its body lifted to the plane and tilted with it.
  const Vec3 n = Vec3(-0.03, 0.02, 1.0).normalized();
  Pose3 body = Pose3::Identity();
  body.linear() = Eigen::Quaterniond::FromTwoVectors(Vec3::UnitZ(), n).toRotationMatrix();
  body.translation() = Vec3(10, 5, 0.03 * 10 - 0.02 * 5);
  int checked = 0;
  lidar.advance_to(
      0.2, [&](Stamp) { return body; },
      [&](Stamp, std::span<const std::uint8_t> pkt) {
        for (const auto& r : decode(pkt)) {
          const Vec3 p = body * mount() * r.p;
          ASSERT_NEAR(p.z(), 0.03 * p.x() - 0.02 * p.y(), 0.003) << p.transpose();  // 2 mm units, 0.01° azimuth
          ++checked;
        }
      });
  EXPECT_GT(checked, 20000);
}

TEST(LidarGeometry, MovingSensorPointsLandOnTheConeWithTheirFiringTimePose) {
  // Car driving at 20 m/s along +x: within one packet (1.3 ms) it moves 2.7 cm, so using one pose per packet, or
  // a wrong firing time, would put points centimetres off. Noise off to see millimetres.
  const double cx = 12.0, cy = -1.0, v = 20.0;
  const World world(make_track({make_cone(cx, cy)}), bare_config(), 1);
  LidarConfig cfg;
  cfg.range_noise = 0.0;
  LidarModel lidar(cfg, world, 1);
  auto body_at = [&](Stamp t) {
    Pose3 T = Pose3::Identity();
    T.translation() = Vec3(v * t, 0, 0);
    return T;
  };
  int cone_points = 0;
  lidar.advance_to(0.45, body_at, [&](Stamp, std::span<const std::uint8_t> pkt) {
    for (const auto& r : decode(pkt)) {
      const Vec3 p = body_at(r.t) * mount() * r.p;
      const double to_cone = small_cone_surface_distance(p, cx, cy);
      ASSERT_LE(std::min(to_cone, std::abs(p.z())), 0.004) << p.transpose() << " t " << r.t;
      cone_points += to_cone < std::abs(p.z()) && p.z() > 0.03;
    }
  });
  EXPECT_GT(cone_points, 100);
}

TEST(LidarGeometry, RangeLimits) {
  const World world(make_track({}), bare_config(), 1);
  LidarConfig cfg;
  cfg.range_noise = 0.0;
  cfg.min_range = 2.0;   // cuts the steep lasers' ground rings (−15° meets the ground at 1.3 m)
  cfg.max_range = 10.0;  // cuts the shallow ones (−1° at 20 m)
  LidarModel lidar(cfg, world, 1);
  int n = 0;
  lidar.advance_to(
      0.1, [](Stamp) { return Pose3::Identity(); },
      [&](Stamp, std::span<const std::uint8_t> pkt) {
        for (const auto& r : decode(pkt)) {
          EXPECT_GE(r.distance, 2.0 - 0.001);
          EXPECT_LE(r.distance, 10.0 + 0.001);
          ++n;
        }
      });
  EXPECT_GT(n, 1000);
}

TEST(LidarGeometry, ConeReturnsAreThePointsDecodedOnEachConeAndNoneFromOneBeyondRange) {
  // Two cones within range (3 and 6 m ahead of the sensor, apart in azimuth) and one beyond max_range. Noise off,
  // so a decoded point is on a cone's surface to the millimetre or on the ground.
  const std::vector<Vec2> cones{{5.0, 1.5}, {8.0, -2.0}, {25.0, 0.0}};
  const World world(make_track({make_cone(cones[0].x(), cones[0].y()), make_cone(cones[1].x(), cones[1].y()),
                                make_cone(cones[2].x(), cones[2].y())}),
                    bare_config(), 1);
  LidarConfig cfg;
  cfg.range_noise = 0.0;
  cfg.max_range = 20.0;
  LidarModel lidar(cfg, world, 1);
  std::vector<int> decoded(cones.size(), 0);
  std::vector<int> counted(cones.size(), 0);
  for (int turn = 1; turn <= 3; ++turn) {
    lidar.advance_to(
        0.1 * turn, [](Stamp) { return Pose3::Identity(); },
        [&](Stamp, std::span<const std::uint8_t> pkt) {
          for (const auto& r : decode(pkt)) {
            const Vec3 p = mount() * r.p;
            for (std::size_t i = 0; i < cones.size(); ++i)
              decoded[i] += small_cone_surface_distance(p, cones[i].x(), cones[i].y()) < std::abs(p.z());
          }
        });
    for (const auto& c : lidar.take_cone_returns()) {
      ASSERT_GE(c.cone, 0);
      ASSERT_LT(c.cone, static_cast<int>(cones.size()));
      EXPECT_GT(c.t, 0.1 * (turn - 1));
      EXPECT_LE(c.t, 0.1 * turn);
      counted[static_cast<std::size_t>(c.cone)] += c.returns;
    }
  }
  EXPECT_GT(decoded[0], 60);
  EXPECT_GT(decoded[1], 15);
  EXPECT_EQ(decoded[2], 0);
  // A point at a cone's foot can lie nearer the ground than the cone's surface: a return or two per turn.
  for (std::size_t i = 0; i < cones.size(); ++i) EXPECT_NEAR(counted[i], decoded[i], 6) << "cone " << i;
  EXPECT_EQ(counted[2], 0);
  EXPECT_TRUE(lidar.take_cone_returns().empty());  // taken: nothing left until the next packets
}

}  // namespace
}  // namespace fsd::sim
