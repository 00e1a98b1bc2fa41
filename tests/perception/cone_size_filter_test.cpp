// The size filter on LiDAR sweeps of hand-placed objects (ray_scene.hpp) from the virtual car's mount: it accepts
// small and big cones and places them at their true base centre, and rejects a lying tyre, a standing tyre, a
// post, a wall segment, a floating object, a kerb-low object and a sparse speck, each for its reason.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <set>

#include "common/rotation.hpp"
#include "perception/clusterer.hpp"
#include "perception/cone_size_filter.hpp"
#include "perception/ground_split.hpp"
#include "tests/perception/ray_scene.hpp"

namespace fsd {
namespace {

using test::RayScene;
using test::SceneObject;

const Pose3 kMount = pose_zyx(Vec3(2.0, 0.0, 0.35), 0, 0, 0);  // body ← sensor, the virtual car's

struct Measured {
  std::vector<ConeMeasurement> all;
  std::vector<Point> cloud;
};

// The scene swept from kMount: its obstacle points in the body frame (above the flat ground's threshold, 5 cm).
std::vector<Point> obstacles_of(const RayScene& scene) {
  Scan scan = scene.sweep(kMount, 40.0);
  for (auto& p : scan.points) {
    const Vec3 b = kMount * Vec3(p.x, p.y, p.z);
    p.x = static_cast<float>(b.x()), p.y = static_cast<float>(b.y()), p.z = static_cast<float>(b.z());
  }
  GroundPlane g;
  g.valid = true;
  std::vector<Point> cloud;
  GroundSplitter().split(scan.points, g, 0.05, 1.0, nullptr, cloud);
  return cloud;
}

// One object (plus the ground) swept from kMount; its obstacle points (body frame) clustered and measured.
Measured measure(const SceneObject& object, double noise = 0.0) {
  RayScene scene;
  scene.objects.push_back(object);
  scene.range_noise = noise;
  GroundPlane g;
  g.valid = true;
  Measured m;
  m.cloud = obstacles_of(scene);
  const auto clusters = Clusterer(ClusterConfig{}).cluster(m.cloud, kMount.translation().head<2>());
  ConeSizeFilter f;
  for (const auto& c : clusters) m.all.push_back(f.measure(m.cloud, c, g, kMount, 0.05, 1));
  return m;
}

// The one cluster measured; fails when the object made none or several.
ConeMeasurement only(const Measured& m) {
  EXPECT_EQ(m.all.size(), 1u);
  return m.all.empty() ? ConeMeasurement{} : m.all.front();
}

TEST(ConeSizeFilter, AcceptsSmallAndBigConesAtTheirBaseCentre) {
  for (double range : {3.0, 6.0, 10.0, 14.0})
    for (double bearing_deg : {0.0, 40.0, 135.0, -100.0}) {
      const double b = deg2rad(bearing_deg);
      const double x = 2.0 + range * std::cos(b), y = range * std::sin(b);
      for (bool big : {false, true}) {
        SCOPED_TRACE(::testing::Message() << "range " << range << " bearing " << bearing_deg << " big " << big);
        const auto m = only(measure(big ? test::big_cone_at(x, y) : test::small_cone_at(x, y)));
        EXPECT_EQ(m.rejection, ConeRejection::None) << to_string(m.rejection);
        // A big cone crossed by one far laser shows five firings across, as a small one would (0.035 m apart at
        // 10 m, its silhouette edge falls between two): it may be placed as a small cone, up to 6 cm short.
        const double tol = big && range >= 10.0 ? 0.06 : 0.03;
        EXPECT_NEAR(m.candidate.position.x(), x, tol);
        EXPECT_NEAR(m.candidate.position.y(), y, tol);
        EXPECT_NEAR(m.candidate.position.z(), 0.0, 1e-9);
        EXPECT_NEAR(m.candidate.range, range, tol);
        // Only a big cone reaches above a small one's tip (where a laser crosses it that high).
        if (!big) {
          EXPECT_FALSE(m.candidate.big);
        } else if (range <= 6.0) {
          EXPECT_TRUE(m.candidate.big);
        }
      }
    }
}

TEST(ConeSizeFilter, PositionWithRangeNoiseStaysWithinFiveCentimetres) {
  for (double range : {4.0, 8.0, 12.0}) {
    const auto m = only(measure(test::small_cone_at(2.0 + range * 0.8, range * 0.6), 0.015));
    EXPECT_EQ(m.rejection, ConeRejection::None);
    EXPECT_NEAR(m.candidate.position.x(), 2.0 + range * 0.8, 0.05);
    EXPECT_NEAR(m.candidate.position.y(), range * 0.6, 0.05);
  }
}

TEST(ConeSizeFilter, CentroidEnvelopeAndCountsAreThoseOfTheClusterPoints) {
  const Measured m = measure(test::small_cone_at(6.0, 1.0));
  const auto c = only(m).candidate;
  ASSERT_GT(c.points, 5u);
  Vec3 sum = Vec3::Zero(), lo = Vec3::Constant(1e9), hi = Vec3::Constant(-1e9);
  std::set<int> rings;
  for (const auto& p : m.cloud) {
    const Vec3 v(p.x, p.y, p.z);
    sum += v, lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
    rings.insert(p.ring);
  }
  EXPECT_EQ(c.points, m.cloud.size());
  EXPECT_EQ(c.cloud.size(), m.cloud.size());
  EXPECT_EQ(c.rings, rings.size());
  EXPECT_TRUE(c.centroid.isApprox(sum / static_cast<double>(m.cloud.size()), 1e-9));
  EXPECT_TRUE(c.min.isApprox(lo, 1e-9));
  EXPECT_TRUE(c.max.isApprox(hi, 1e-9));
  EXPECT_NEAR(c.height, hi.z(), 1e-9);  // flat ground at z = 0
  EXPECT_NEAR(c.bottom, lo.z(), 1e-9);
  // The visible half lies in front of the base centre: the centroid is nearer to the sensor than the cone.
  EXPECT_LT((c.centroid.head<2>() - kMount.translation().head<2>()).norm(), c.range);
}

TEST(ConeSizeFilter, RejectsWhatIsNoCone) {
  struct Case {
    const char* what;
    SceneObject object;
    std::vector<ConeRejection> reasons;
  };
  SceneObject floating = test::cylinder_at(7.0, 0.5, 0.1, 0.15, 0.3);  // a box in the air, 0.3-0.45 m up
  SceneObject kerb = test::cylinder_at(5.0, -0.5, 0.1, 0.12);          // lower than any cone
  const std::vector<Case> cases{
      {"lying tyre", test::cylinder_at(7.0, 2.0, 0.3, 0.2), {ConeRejection::TooWide}},
      {"standing tyre, tread on",
       test::standing_tyre_at(6.0, 0.0, std::numbers::pi / 2),
       {ConeRejection::TooTall, ConeRejection::NotConeShaped}},
      {"standing tyre, side on", test::standing_tyre_at(6.0, 0.0, 0.0), {ConeRejection::TooWide}},
      {"post", test::cylinder_at(8.0, -1.0, 0.05, 1.2), {ConeRejection::TooTall}},
      {"wall segment", test::wall_at(9.0, -1.0, 1.2, 2.0, 1.0), {ConeRejection::TooWide}},
      {"floating box", floating, {ConeRejection::Floating}},
      {"kerb-low block", kerb, {ConeRejection::TooFlat}},
  };
  for (const auto& c : cases) {
    const auto m = only(measure(c.object));
    EXPECT_TRUE(std::find(c.reasons.begin(), c.reasons.end(), m.rejection) != c.reasons.end())
        << c.what << ": " << to_string(m.rejection);
  }
}

TEST(ConeSizeFilter, RejectsASparseSpeckForItsRange) {
  std::vector<Point> cloud(2);
  cloud[0].x = 6.0f, cloud[0].z = 0.2f;
  cloud[1].x = 6.02f, cloud[1].z = 0.22f;
  GroundPlane g;
  const ConeSizeFilter f;
  Cluster c;
  c.indices = {0, 1};
  // A small cone 4 m from the sensor returns dozens of points per frame; two are a speck.
  EXPECT_GT(f.expected_points(4.0, 1, 0.05), 10.0);
  EXPECT_EQ(f.measure(cloud, c, g, kMount, 0.05, 1).rejection, ConeRejection::TooSparse);
  // Far away two points are what a cone gives.
  for (auto& p : cloud) p.x += 14.0f, p.z = 0.1f;
  EXPECT_EQ(f.measure(cloud, c, g, kMount, 0.05, 1).rejection, ConeRejection::None);
}

TEST(ConeSizeFilter, APartlyHiddenConeIsExpectedToShowOnlyItsUnhiddenPart) {
  // A cone 1 m behind another and 8 cm to the side, from kMount. The far one spans −0.65°..3.71° (its base); the
  // nearer one's returns above the ground threshold (its lowest laser at 0.10 m, radius 0.086 m, 2 m away) cover
  // ±2.46°, so 0.65 + 2.46 of its 4.36° are hidden: 29 % of its azimuths show (somewhat more about the measured
  // position, which lies towards the part that shows).
  RayScene scene;
  const Vec2 near = kMount.translation().head<2>() + Vec2(2.0, 0.0), far = near + Vec2(1.0, 0.08);
  scene.objects.push_back(test::small_cone_at(near.x(), near.y()));
  scene.objects.push_back(test::small_cone_at(far.x(), far.y()));
  GroundPlane g;
  g.valid = true;
  const std::vector<Point> cloud = obstacles_of(scene);
  const auto clusters = Clusterer(ClusterConfig{}).cluster(cloud, kMount.translation().head<2>());
  ASSERT_EQ(clusters.size(), 2u);
  LidarShadow shadow;
  shadow.build(cloud, kMount.translation().head<2>());
  const ConeSizeFilter f;
  // Three frames' worth expected, one frame's cloud: the open cone still shows enough, the hidden one not for a
  // whole cone, but for the part the nearer one leaves.
  for (const auto& c : clusters) {
    const auto open = f.measure(cloud, c, g, kMount, 0.05, 3);
    const auto seen = f.measure(cloud, c, g, kMount, 0.05, 3, &shadow);
    if ((open.candidate.position.head<2>() - near).norm() < 0.1) {
      EXPECT_EQ(open.rejection, ConeRejection::None);
      EXPECT_DOUBLE_EQ(seen.visible_share, 1.0);
      EXPECT_EQ(seen.rejection, ConeRejection::None);
    } else {
      EXPECT_LT((seen.candidate.position.head<2>() - far).norm(), 0.1);
      EXPECT_EQ(open.rejection, ConeRejection::TooSparse);
      EXPECT_GT(seen.visible_share, 0.2);
      EXPECT_LT(seen.visible_share, 0.5);
      EXPECT_EQ(seen.rejection, ConeRejection::None);
    }
  }
}

TEST(ConeSizeFilter, BesideSomethingTaller) {
  std::vector<Point> cloud(1);
  cloud[0].x = 10.0f, cloud[0].y = 0.5f, cloud[0].z = 0.9f;  // the top of a post 0.5 m from a candidate
  const ConeSizeFilter f;
  GroundPlane g;
  const auto tall = f.tall_points(cloud, g);
  ASSERT_EQ(tall.size(), 1u);
  EXPECT_TRUE(f.beside_taller(Vec3(10.0, 0.0, 0.0), tall));
  EXPECT_FALSE(f.beside_taller(Vec3(10.0, -0.5, 0.0), tall));
}

}  // namespace
}  // namespace fsd
