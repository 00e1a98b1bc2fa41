// Clustering on hand-made point sets of known membership: both methods find the same objects, with the right
// counts, centroids and envelopes; the grid method's range-aware tolerance keeps a sparse far object whole.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "perception/clusterer.hpp"

namespace fsd {
namespace {

Point at(double x, double y, double z) {
  Point p;
  p.x = static_cast<float>(x), p.y = static_cast<float>(y), p.z = static_cast<float>(z);
  return p;
}

// A ring of points around (cx, cy) with radius r at heights z0..z1: a cone-like blob.
void blob(std::vector<Point>& out, double cx, double cy, double r, int n, double z0, double z1) {
  for (int i = 0; i < n; ++i) {
    const double a = 2 * 3.14159265358979 * i / n;
    out.push_back(at(cx + r * std::cos(a), cy + r * std::sin(a), z0 + (z1 - z0) * (i % 5) / 4.0));
  }
}

std::set<std::set<std::uint32_t>> partition(const std::vector<Cluster>& cs) {
  std::set<std::set<std::uint32_t>> out;
  for (const auto& c : cs) out.insert(std::set<std::uint32_t>(c.indices.begin(), c.indices.end()));
  return out;
}

class ClustererMethods : public ::testing::TestWithParam<std::string> {};

TEST_P(ClustererMethods, FindsEachObjectWithExactlyItsPoints) {
  std::vector<Point> pts;
  blob(pts, 5.0, 1.0, 0.1, 20, 0.05, 0.30);    // 0..19
  blob(pts, 5.0, 1.5, 0.1, 12, 0.05, 0.25);    // 20..31: 0.5 m from the first (a timing line's doubled cones)
  blob(pts, -3.0, -4.0, 0.14, 30, 0.05, 0.5);  // 32..61
  pts.push_back(at(10, 10, 0.1));              // 62: a lone point
  ClusterConfig cfg;
  cfg.method = GetParam();
  cfg.min_points = 2;
  Clusterer c(cfg);
  const auto clusters = c.cluster(pts, Vec2(0, 0));
  ASSERT_EQ(clusters.size(), 3u);  // the lone point is below min_points
  std::set<std::set<std::uint32_t>> expected;
  for (auto [b, e] : {std::pair{0u, 20u}, {20u, 32u}, {32u, 62u}}) {
    std::set<std::uint32_t> s;
    for (auto i = b; i < e; ++i) s.insert(i);
    expected.insert(s);
  }
  EXPECT_EQ(partition(clusters), expected);
  // Order: by first point.
  EXPECT_EQ(clusters[0].indices.size(), 20u);
  EXPECT_EQ(clusters[1].indices.size(), 12u);
  EXPECT_EQ(clusters[2].indices.size(), 30u);
}

TEST_P(ClustererMethods, DropsClustersAboveTheSizeBound) {
  std::vector<Point> wall;
  for (int i = 0; i < 400; ++i) wall.push_back(at(8.0, -5.0 + 0.025 * i, 0.5));
  blob(wall, 3, 3, 0.1, 10, 0.1, 0.3);
  ClusterConfig cfg;
  cfg.method = GetParam();
  cfg.max_points = 100;
  std::size_t too_large = 0;
  const auto clusters = Clusterer(cfg).cluster(wall, Vec2(0, 0), &too_large);
  ASSERT_EQ(clusters.size(), 1u);
  EXPECT_EQ(clusters[0].indices.size(), 10u);
  EXPECT_EQ(too_large, 1u);
}

INSTANTIATE_TEST_SUITE_P(Methods, ClustererMethods, ::testing::Values("grid", "pcl_euclidean"));

TEST(Clusterer, RangeAwareToleranceKeepsASparseFarObjectWhole) {
  // Returns of one object at 30 m, 0.25 m apart (a lost return between firings 0.1 m apart): beyond a 0.2 m
  // tolerance, within 0.01 · 30 m = 0.3 m.
  std::vector<Point> pts;
  for (int i = 0; i < 4; ++i) pts.push_back(at(30.0, 0.25 * i, 0.2));
  ClusterConfig fixed;
  fixed.range_factor = 0.0;
  EXPECT_EQ(Clusterer(fixed).cluster(pts, Vec2(0, 0)).size(), 0u);  // four single points, below min_points 2
  ClusterConfig aware;                                              // range_factor 0.01
  const auto c = Clusterer(aware).cluster(pts, Vec2(0, 0));
  ASSERT_EQ(c.size(), 1u);
  EXPECT_EQ(c[0].indices.size(), 4u);
  // Near the sensor the same spacing splits: the tolerance only grows with range.
  for (auto& p : pts) p.x = 3.0f;
  EXPECT_EQ(Clusterer(aware).cluster(pts, Vec2(0, 0)).size(), 0u);
}

TEST(Clusterer, HeightWeightSplitsStackedObjects) {
  std::vector<Point> pts;
  for (int i = 0; i < 5; ++i) pts.push_back(at(4.0 + 0.02 * i, 0, 0.1));
  for (int i = 0; i < 5; ++i) pts.push_back(at(4.0 + 0.02 * i, 0, 0.9));      // 0.8 m above, same footprint
  EXPECT_EQ(Clusterer(ClusterConfig{}).cluster(pts, Vec2(0, 0)).size(), 1u);  // footprint only: one object
  ClusterConfig weighted;
  weighted.z_weight = 1.0;
  EXPECT_EQ(Clusterer(weighted).cluster(pts, Vec2(0, 0)).size(), 2u);
  weighted.method = "pcl_euclidean";
  EXPECT_EQ(Clusterer(weighted).cluster(pts, Vec2(0, 0)).size(), 2u);
}

}  // namespace
}  // namespace fsd
