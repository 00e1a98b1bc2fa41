// match_to_map against poses whose error is known: cones seen from the true pose, placed by an estimate off by a
// known rigid motion; the alignment must give the true pose back; too few pairs, an implausible jump and a disabled
// matcher give nothing.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "localization/map_match.hpp"

namespace fsd {
namespace {

// Two boundaries of a bending lane, one doubled cone 0.5 m from its neighbour (a timing line's).
std::vector<Cone> lane() {
  std::vector<Cone> map;
  for (int k = 0; k < 6; ++k) {
    const double x = 3.0 * k, bend = 0.02 * x * x;
    for (const double side : {-1.6, 1.6}) {
      Cone c;
      c.position = Vec3(x, side + bend, 0);
      map.push_back(c);
    }
  }
  Cone doubled;
  doubled.position = Vec3(6.5, 1.6 + 0.02 * 36, 0);
  map.push_back(doubled);
  return map;
}

// The map's cones as a detector at `truth` sees them (vehicle frame), within `range`.
std::vector<Cone> seen_from(const Pose2& truth, const std::vector<Cone>& map, double range = 15.0) {
  std::vector<Cone> out;
  for (const auto& c : map) {
    const Vec2 v = truth.inverse_transform(c.position.head<2>());
    if (v.norm() > range) continue;
    Cone d;
    d.position = Vec3(v.x(), v.y(), 0);
    out.push_back(d);
  }
  return out;
}

TEST(MapMatch, TheAlignmentGivesTheTruePoseBack) {
  const auto map = lane();
  const Pose2 truth{2.0, 0.3, 0.05};
  const Pose2 estimate = Pose2{0.15, -0.1, 0.02} * truth;  // off by 0.18 m and 1.1°
  const auto m = match_to_map(seen_from(truth, map), estimate, map);
  ASSERT_TRUE(m);
  EXPECT_EQ(m->pairs, static_cast<int>(seen_from(truth, map).size()));
  EXPECT_LT(m->rms_after, 1e-9);
  EXPECT_GT(m->rms_before, 0.1);
  const Pose2 corrected = m->alignment * estimate;
  EXPECT_NEAR(corrected.x, truth.x, 1e-9);
  EXPECT_NEAR(corrected.y, truth.y, 1e-9);
  EXPECT_NEAR(corrected.yaw, truth.yaw, 1e-9);
}

TEST(MapMatch, TooFewPairsAnImplausibleJumpOrOffGiveNothing) {
  const auto map = lane();
  const Pose2 truth{2.0, 0.3, 0.05};
  const auto seen = seen_from(truth, map);
  // Three cones only.
  EXPECT_FALSE(match_to_map(std::vector<Cone>(seen.begin(), seen.begin() + 3), truth, map));
  // Off by 0.5 m: every cone still within the 0.7 m gate of its own, but a 0.5 m step is no frame's drift.
  EXPECT_FALSE(match_to_map(seen, Pose2{0.5, 0.0, 0.0} * truth, map));
  MapMatchConfig wide;
  wide.max_step = 1.0;
  EXPECT_TRUE(match_to_map(seen, Pose2{0.5, 0.0, 0.0} * truth, map, wide));
  MapMatchConfig off;
  off.enabled = false;
  EXPECT_FALSE(match_to_map(seen, Pose2{0.1, 0.0, 0.0} * truth, map, off));
  EXPECT_FALSE(match_to_map(seen, truth, {}));
}

}  // namespace
}  // namespace fsd
