// hidden_share against shares worked out by hand: boxes in front of a small cone's body (0.228 m base, 0.025 m
// tip radius, 0.325 m tall) at 100 px/m, so the body spans x ∈ [-11.4, 11.4] px at its base and 32.5 px up.
#include <gtest/gtest.h>

#include <vector>

#include "perception/camera/occlusion.hpp"

namespace fsd {
namespace {

const cv::Point2d kBase(100, 200);
constexpr double kScale = 100;

TEST(Occlusion, NothingInFrontHidesNothing) {
  EXPECT_EQ(hidden_share(kBase, kScale, {}), 0.0);
  const std::vector<ImageSilhouette> beside{{{140, 200}, kScale, 0.114, 0.325}};  // 40 px to the right
  EXPECT_EQ(hidden_share(kBase, kScale, beside), 0.0);
}

TEST(Occlusion, ABiggerConeRightInFrontHidesAll) {
  const std::vector<ImageSilhouette> front{{{100, 205}, 110, 0.1425, 0.505}};
  EXPECT_EQ(hidden_share(kBase, kScale, front), 1.0);
}

TEST(Occlusion, AHalfWidthBoxHidesHalf) {
  // A tall box covering x >= 100 (the body's right half): the body is symmetric, so half its samples.
  const std::vector<ImageSilhouette> right{{{200, 300}, kScale, 1.0, 2.0}};
  EXPECT_NEAR(hidden_share(kBase, kScale, right), 0.5, 1e-9);
}

TEST(Occlusion, ALowBoxHidesTheBottomRows) {
  // A wide box 0.1625 m tall on the same base: the lower half of the body's height, all its width there.
  const std::vector<ImageSilhouette> low{{kBase, kScale, 1.0, 0.1625}};
  EXPECT_NEAR(hidden_share(kBase, kScale, low), 0.5, 1e-9);
}

TEST(Occlusion, UnknownScaleHidesNothing) {
  const std::vector<ImageSilhouette> front{{kBase, kScale, 1.0, 1.0}};
  EXPECT_EQ(hidden_share(kBase, 0.0, front), 0.0);
}

}  // namespace
}  // namespace fsd
