// Which cones the LiDAR could see at a frame, from the simulator's per-cone returns: summed over the window up to
// the frame's last firing, at least the minimum count, nothing after the frame; and the perception score's
// recall over those cones only.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "daemon/scoring/lidar_visibility.hpp"
#include "daemon/scoring/perception_score.hpp"
#include "tests/cone_at.hpp"

namespace fsd {
namespace {

TEST(LidarVisibility, ReturnsSummedOverTheWindowUpToTheFrame) {
  LidarVisibility v;  // 0.3 s, 2 returns
  EXPECT_FALSE(v.known());
  v.add({});
  EXPECT_TRUE(v.known());  // the LiDAR runs, it saw nothing yet
  EXPECT_TRUE(v.visible_at(1.0).empty());
  v.add({{7, 1, 0.60}, {3, 5, 0.62}});
  v.add({{7, 1, 0.85}, {9, 1, 0.88}});
  v.add({{11, 4, 1.05}});
  // At 0.9, the window (0.6, 0.9]: cone 3's 5 returns; cone 7's 0.60 is out, so it has 1; cone 9 has 1.
  EXPECT_EQ(v.visible_at(0.9), (std::vector<std::uint32_t>{3}));
  EXPECT_EQ(v.visible_at(0.91), (std::vector<std::uint32_t>{3}));  // (0.61, 0.91]: cone 3's 0.62 still in
  EXPECT_TRUE(v.visible_at(0.95).empty());                         // cone 3 gone; cone 11 is after the frame
  EXPECT_EQ(v.visible_at(1.1), (std::vector<std::uint32_t>{11}));
  // A wider window, one return enough, entries out of order: every cone in (0.5, 1.1], sorted.
  LidarVisibility wide({.window = 0.6, .min_returns = 1});
  wide.add({{7, 1, 0.60}, {3, 5, 0.62}});
  wide.add({{11, 4, 1.05}, {9, 1, 0.88}});
  EXPECT_EQ(wide.visible_at(1.1), (std::vector<std::uint32_t>{3, 7, 9, 11}));
}

TEST(LidarVisibility, KeepsOnlyTheLastSeconds) {
  LidarVisibility v({.window = 0.3, .min_returns = 1, .keep = 1.0});
  v.add({{1, 3, 0.5}});
  v.add({{2, 3, 2.0}});  // 1.5 s later: the first is forgotten
  EXPECT_TRUE(v.visible_at(0.5).empty());
  EXPECT_EQ(v.visible_at(2.0), (std::vector<std::uint32_t>{2}));
  LidarVisibility bounded({.window = 10, .min_returns = 1, .keep = 100, .max_entries = 2});
  bounded.add({{1, 1, 0.1}, {2, 1, 0.2}, {3, 1, 0.3}});
  EXPECT_EQ(bounded.visible_at(1.0), (std::vector<std::uint32_t>{2, 3}));
}

TEST(PerceptionScore, RecallOverTheVisibleConesWithin15m) {
  // The car at the origin heading +x; true cones at 5, 8, 12 and 20 m (ids 1-4); the 8 m one hidden (not visible),
  // the 12 m one visible but missed.
  auto cone = [](double x, std::uint32_t id) {
    Cone c = test::cone_at(x, 0.5, ConeColour::Blue);
    c.id = id;
    return c;
  };
  const std::vector<Cone> truth{cone(5, 1), cone(8, 2), cone(12, 3), cone(20, 4)};
  ConeDetections det;
  det.cones = {test::cone_at(5, 0.5, ConeColour::Blue)};
  const std::vector<std::uint32_t> visible{1, 3, 4};
  PerceptionScore score;
  score.add_frame(det, truth, Pose2{});
  EXPECT_FALSE(score.to_json().contains("recall_visible_15m"));  // not known for that frame
  score.add_frame(det, truth, Pose2{}, &visible);
  const auto j = score.to_json();
  EXPECT_NEAR(j["recall_15m"].get<double>(), 2.0 / 6.0, 5e-5);    // 1 of 3 within 15 m, twice
  EXPECT_NEAR(j["recall_visible_15m"].get<double>(), 0.5, 5e-5);  // 5 m found, 12 m missed; 8 m hidden, 20 m far
}

}  // namespace
}  // namespace fsd
