// The kinematic bicycle's two directions against hand-computed values: the curvature of a wheel angle and back.
#include <gtest/gtest.h>

#include <cmath>

#include "common/car.hpp"

namespace fsd {
namespace {

TEST(KinematicBicycle, CurvatureOfAWheelAngleAndBack) {
  // At the lock of the default car (0.5 rad, wheelbase 1.53 m): tan(0.5) / 1.53 = 0.35706 1/m, a 2.80 m radius.
  EXPECT_NEAR(kinematic_curvature(0.5, 1.53), 0.35706, 1e-5);
  EXPECT_NEAR(kinematic_curvature(-0.5, 1.53), -0.35706, 1e-5);  // right turns are negative
  EXPECT_EQ(kinematic_curvature(0.3, 0.0), 0.0);                  // no wheelbase: no turn, not a division by zero
  EXPECT_NEAR(kinematic_steer(0.35706, 1.53), 0.5, 1e-5);
  EXPECT_NEAR(kinematic_steer(0.1, 2.0), std::atan(0.2), 1e-12);
}

}  // namespace
}  // namespace fsd
