// Ground homography (the paper's 4-point perspective transform) against a synthetic pinhole camera whose
// projection is written out by hand here.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "common/camera_geometry.hpp"

namespace fsd {
namespace {

// Camera 1.2 m above the ground, 0.5 m ahead of the rear axle, pitched down by 0.15 rad; fx = fy = 500, principal
// point (320, 240). A ground point (X, Y) seen from it: d = (X − 0.5, Y, −1.2); in the pitched camera body frame
// m = (c·dx − s·dz, dy, s·dx + c·dz); optical (x right, y down, z forward) = (−m.y, −m.z, m.x).
constexpr double kFx = 500, kFy = 500, kCx = 320, kCy = 240, kMountX = 0.5, kHeight = 1.2, kPitch = 0.15;

Vec2 project_by_hand(double X, double Y) {
  const double c = std::cos(kPitch), s = std::sin(kPitch);
  const double dx = X - kMountX, dy = Y, dz = -kHeight;
  const double mx = c * dx - s * dz, my = dy, mz = s * dx + c * dz;
  return {kCx + kFx * (-my) / mx, kCy + kFy * (-mz) / mx};
}

const PointQuad kGround{Vec2(5, 1.5), Vec2(5, -1.5), Vec2(12, -1.5), Vec2(12, 1.5)};

PointQuad image_of(const PointQuad& ground) {
  PointQuad q;
  for (std::size_t i = 0; i < 4; ++i) q[i] = project_by_hand(ground[i].x(), ground[i].y());
  return q;
}

void expect_matches_camera(const GroundHomography& h) {
  for (double X = 3.0; X <= 30.0; X += 3.0)
    for (double Y = -5.0; Y <= 5.0; Y += 2.5) {
      const Vec2 truth = project_by_hand(X, Y);
      const auto px = ground_to_image(h, {X, Y});
      ASSERT_TRUE(px) << X << "," << Y;
      EXPECT_NEAR(px->x(), truth.x(), 0.5) << "ground " << X << "," << Y;
      EXPECT_NEAR(px->y(), truth.y(), 0.5) << "ground " << X << "," << Y;
      // And back: the pixel's ground point, within a millimetre per metre of range.
      const auto g = image_to_ground(h, truth);
      ASSERT_TRUE(g);
      EXPECT_NEAR(g->x(), X, 1e-3 * X);
      EXPECT_NEAR(g->y(), Y, 1e-3 * X);
    }
}

TEST(GroundHomography, FourPointsReproduceThePinholeCamera) {
  expect_matches_camera(compute_ground_homography(image_of(kGround), kGround));
}

TEST(GroundHomography, PointOrderDoesNotMatterIfBothListsAgree) {
  const PointQuad ground{kGround[2], kGround[0], kGround[3], kGround[1]};  // crossed, but the same in both lists
  expect_matches_camera(compute_ground_homography(image_of(ground), ground));
}

TEST(GroundHomography, PinholeModelGivesTheSameMapping) {
  Eigen::Matrix3d K;
  K << kFx, 0, kCx, 0, kFy, kCy, 0, 0, 1;
  // Body ← optical: camera body pitched down about y, optical axes (x right, y down, z forward).
  Eigen::Matrix3d optical_axes;
  optical_axes << 0, 0, 1, -1, 0, 0, 0, -1, 0;
  Pose3 T = Pose3::Identity();
  T.linear() = Eigen::AngleAxisd(kPitch, Vec3::UnitY()).toRotationMatrix() * optical_axes;
  T.translation() = Vec3(kMountX, 0, kHeight);
  expect_matches_camera(pinhole_ground_homography(K, T));
}

TEST(GroundHomography, HorizonAndBehindTheCameraHaveNoImage) {
  const GroundHomography h = compute_ground_homography(image_of(kGround), kGround);
  // The horizon is at v = cy − fy·tan(pitch) = 164.4: rows above it show sky.
  EXPECT_FALSE(image_to_ground(h, {320, 150}));
  EXPECT_FALSE(image_to_ground(h, {320, 0}));
  EXPECT_TRUE(image_to_ground(h, {320, 180}));
  EXPECT_FALSE(ground_to_image(h, {-3.0, 0.0}));  // behind the car
  EXPECT_TRUE(ground_to_image(h, {3.0, 0.0}));
}

TEST(GroundHomography, DegeneratePointsAreRejected) {
  const PointQuad image = image_of(kGround);
  PointQuad collinear = image;
  collinear[2] = (image[0] + image[1]) * 0.5;  // on the line through points 1 and 2
  EXPECT_THROW(compute_ground_homography(collinear, kGround), HomographyError);
  PointQuad repeated = kGround;
  repeated[3] = repeated[0];
  EXPECT_THROW(compute_ground_homography(image, repeated), HomographyError);
  PointQuad nearly = kGround;
  nearly[2] = Vec2(12, 1.5 + 1e-5);  // 12,1.5 and 12,−1.5 and 12,1.50001: three on x = 12
  nearly[1] = Vec2(12, -1.5);
  EXPECT_THROW(compute_ground_homography(image, nearly), HomographyError);
  PointQuad nan = image;
  nan[1].x() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(compute_ground_homography(nan, kGround), HomographyError);
  // Ground points in another order than the pixels: no camera sees that.
  const PointQuad swapped{kGround[0], kGround[1], kGround[3], kGround[2]};
  try {
    compute_ground_homography(image, swapped);
    FAIL() << "swapped order accepted";
  } catch (const HomographyError& e) {
    EXPECT_NE(std::string(e.what()).find("order"), std::string::npos) << e.what();
  }
  EXPECT_THROW(make_ground_homography(Eigen::Matrix3d::Zero()), HomographyError);
  Eigen::Matrix3d singular;
  singular << 1, 2, 3, 2, 4, 6, 0, 0, 1;
  EXPECT_THROW(make_ground_homography(singular), HomographyError);
}

}  // namespace
}  // namespace fsd
