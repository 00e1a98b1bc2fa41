#include <gtest/gtest.h>

#include "common/geometry.hpp"

namespace fsd {
namespace {

TEST(Geometry, WrapAngle) {
  EXPECT_NEAR(wrap_angle(3 * std::numbers::pi), std::numbers::pi, 1e-12);
  EXPECT_NEAR(wrap_angle(-std::numbers::pi), std::numbers::pi, 1e-12);
  EXPECT_NEAR(wrap_angle(0.5 + 4 * std::numbers::pi), 0.5, 1e-12);
}

TEST(Geometry, Pose2ComposeAndInverseByHand) {
  const Pose2 a{1.0, 2.0, std::numbers::pi / 2};
  // A point 1 m ahead of a car facing +y at (1, 2) is at (1, 3).
  const Vec2 p = a.transform({1.0, 0.0});
  EXPECT_NEAR(p.x(), 1.0, 1e-12);
  EXPECT_NEAR(p.y(), 3.0, 1e-12);
  const Vec2 back = a.inverse_transform(p);
  EXPECT_NEAR(back.x(), 1.0, 1e-12);
  EXPECT_NEAR(back.y(), 0.0, 1e-12);
  const Pose2 id = a * a.inverse();
  EXPECT_NEAR(id.x, 0, 1e-12);
  EXPECT_NEAR(id.y, 0, 1e-12);
  EXPECT_NEAR(id.yaw, 0, 1e-12);
  const Pose2 b = to_pose2(a.to_pose3(0.3));
  EXPECT_NEAR(b.yaw, a.yaw, 1e-12);
}

}  // namespace
}  // namespace fsd
