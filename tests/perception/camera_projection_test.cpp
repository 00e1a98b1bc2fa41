// The camera stage's projection of LiDAR candidates into the image, against a pinhole camera whose projection is
// written out by hand here: the paper's homography from four known point pairs, the calibrated pinhole (with and
// without lens distortion), an ROI whose size follows the range, and what stays unverified.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "perception/camera/cone_projection.hpp"

namespace fsd {
namespace {

// Camera 1.2 m above the ground, 0.5 m ahead of the rear axle, pitched down by 0.15 rad; fx = fy = 500, principal
// point (320, 240), 640 × 480. A body point (X, Y, Z) seen from it: d = (X − 0.5, Y, Z − 1.2); in the pitched camera
// frame m = (c·dx − s·dz, dy, s·dx + c·dz); optical (x right, y down, z forward) = (−m.y, −m.z, m.x).
constexpr double kF = 500, kCx = 320, kCy = 240, kMountX = 0.5, kHeight = 1.2, kPitch = 0.15;

struct Optical {
  double x, y, z;
};
Optical optical_by_hand(double X, double Y, double Z, double pitch = kPitch) {
  const double c = std::cos(pitch), s = std::sin(pitch);
  const double dx = X - kMountX, dy = Y, dz = Z - kHeight;
  return {-dy, -(s * dx + c * dz), c * dx - s * dz};
}
cv::Point2d pixel_by_hand(double X, double Y, double Z, double pitch = kPitch, double k1 = 0.0) {
  const Optical o = optical_by_hand(X, Y, Z, pitch);
  const double xn = o.x / o.z, yn = o.y / o.z, radial = 1 + k1 * (xn * xn + yn * yn);
  return {kCx + kF * xn * radial, kCy + kF * yn * radial};
}

CameraIntrinsics intrinsics(double k1 = 0.0) {
  CameraIntrinsics in;
  in.width = 640;
  in.height = 480;
  in.K << kF, 0, kCx, 0, kF, kCy, 0, 0, 1;
  if (k1 != 0.0) in.distortion = {k1, 0, 0, 0, 0};
  return in;
}

CameraCalibration pinhole(double pitch = kPitch, double k1 = 0.0) {
  CameraCalibration c;
  c.intrinsics = intrinsics(k1);
  c.extrinsics = CameraMount{kMountX, 0, kHeight, 0, pitch, 0};
  return c;
}

// The paper's calibration: four ground markers and the pixels where the camera sees them.
CameraCalibration homography_only(double pitch = kPitch) {
  const PointQuad ground{Vec2(5, 1.5), Vec2(5, -1.5), Vec2(12, -1.5), Vec2(12, 1.5)};
  PointQuad image;
  for (std::size_t i = 0; i < 4; ++i) {
    const cv::Point2d p = pixel_by_hand(ground[i].x(), ground[i].y(), 0.0, pitch);
    image[i] = Vec2(p.x, p.y);
  }
  CameraCalibration c;
  c.homography = HomographyCalibration{compute_ground_homography(image, ground), image, ground};
  return c;
}

ConeProjectionConfig homography_model() {
  ConeProjectionConfig cfg;
  cfg.model = "homography";
  return cfg;
}

const cv::Size kImage(640, 480);

TEST(CameraProjection, HomographyFromFourPointPairsPutsCandidatesOnTheirPixels) {
  const ConeProjector projector(homography_only(), homography_model());
  EXPECT_FALSE(projector.pinhole());
  for (const Vec3& g : {Vec3(4, 0, 0), Vec3(8, 1.5, 0), Vec3(10, -2.5, 0), Vec3(15, 3, 0), Vec3(20, -1, 0)}) {
    const CandidateRoi roi = projector.project(g, kImage);
    ASSERT_EQ(roi.status, RoiStatus::Inside) << g.transpose();
    const cv::Point2d truth = pixel_by_hand(g.x(), g.y(), 0.0);
    EXPECT_NEAR(roi.base.x, truth.x, 0.05) << g.transpose();
    EXPECT_NEAR(roi.base.y, truth.y, 0.05) << g.transpose();
    // The ROI stands on the base point: roi_below under it, roi_height over it, centred.
    EXPECT_NEAR(roi.box.x + roi.box.width / 2, truth.x, 1e-6);
    EXPECT_NEAR(roi.box.y + roi.box.height, truth.y + 0.06 * roi.px_per_m, 1e-6);
    EXPECT_NEAR(roi.box.height / roi.box.width, (0.58 + 0.06) / 0.44, 1e-9);
  }
}

TEST(CameraProjection, PinholeProjectsTheRoiCornersToHandComputedPixels) {
  for (const double k1 : {0.0, -0.2}) {
    SCOPED_TRACE(k1 == 0.0 ? "no distortion" : "barrel distortion k1 = -0.2");
    const ConeProjector projector(pinhole(kPitch, k1));
    EXPECT_TRUE(projector.pinhole());
    for (const Vec3& g : {Vec3(5, 0, 0), Vec3(8, 1.5, 0), Vec3(12, -2, 0.05), Vec3(18, 2.5, 0)}) {
      const CandidateRoi roi = projector.project(g, kImage);
      ASSERT_EQ(roi.status, RoiStatus::Inside) << g.transpose();
      const cv::Point2d base = pixel_by_hand(g.x(), g.y(), g.z(), kPitch, k1);
      EXPECT_NEAR(roi.base.x, base.x, 1e-6);
      EXPECT_NEAR(roi.base.y, base.y, 1e-6);
      // Corners: 0.22 m either side across the line of sight from the camera, 0.06 m below and 0.58 m above.
      const Vec2 sight = (g.head<2>() - Vec2(kMountX, 0)).normalized(), across(-sight.y() * 0.22, sight.x() * 0.22);
      double u0 = 1e9, u1 = -1e9, v0 = 1e9, v1 = -1e9;
      for (const double side : {-1.0, 1.0})
        for (const double z : {g.z() - 0.06, g.z() + 0.58}) {
          const cv::Point2d p = pixel_by_hand(g.x() + side * across.x(), g.y() + side * across.y(), z, kPitch, k1);
          u0 = std::min(u0, p.x), u1 = std::max(u1, p.x), v0 = std::min(v0, p.y), v1 = std::max(v1, p.y);
        }
      EXPECT_NEAR(roi.box.x, u0, 1e-6);
      EXPECT_NEAR(roi.box.x + roi.box.width, u1, 1e-6);
      EXPECT_NEAR(roi.box.y, v0, 1e-6);
      EXPECT_NEAR(roi.box.y + roi.box.height, v1, 1e-6);
    }
  }
}

// A level camera sees an upright 0.64 m tall ROI straight ahead at depth d − 0.5 m as f·0.64/(d − 0.5) pixels.
TEST(CameraProjection, RoiSizeFollowsTheRange) {
  const ConeProjector pin(pinhole(0.0));
  const ConeProjector hom(homography_only(0.0), homography_model());
  for (const double d : {4.0, 6.0, 10.0, 15.0, 20.0}) {
    const double expected = kF * 0.64 / (d - kMountX);
    const CandidateRoi a = pin.project(Vec3(d, 0, 0), kImage), b = hom.project(Vec3(d, 0, 0), kImage);
    ASSERT_EQ(a.status, RoiStatus::Inside) << d;
    ASSERT_EQ(b.status, RoiStatus::Inside) << d;
    EXPECT_NEAR(a.box.height, expected, 1e-6 * expected) << d;
    EXPECT_NEAR(b.box.height, expected, 1e-3 * expected) << d;
    EXPECT_NEAR(a.box.width, kF * 0.44 / (d - kMountX), 1e-6 * expected) << d;
    EXPECT_NEAR(a.px_per_m, kF / (d - kMountX), 1e-6 * expected) << d;
  }
}

TEST(CameraProjection, CandidatesTheCameraCannotSeeStayUnverified) {
  const ConeProjector projector(pinhole());
  EXPECT_EQ(projector.project(Vec3(-3, 0, 0), kImage).status, RoiStatus::Outside);   // behind the car
  EXPECT_EQ(projector.project(Vec3(0.5, 0, 0), kImage).status, RoiStatus::Outside);  // under the camera
  EXPECT_EQ(projector.project(Vec3(5, 12, 0), kImage).status, RoiStatus::Outside);   // far to the side
  EXPECT_EQ(projector.project(Vec3(1.5, 0, 0), kImage).status, RoiStatus::Outside);  // base below the image
  // Half of the ROI past the left edge: u = 320 − 500·Y/depth = 0 at Y ≈ 6.44 for a depth of 10.07 m.
  const CandidateRoi edge = projector.project(Vec3(10.5, 6.45, 0), kImage);
  EXPECT_EQ(edge.status, RoiStatus::Outside) << edge.box.x << " " << edge.box.width;
  EXPECT_EQ(projector.project(Vec3(10.5, 5.5, 0), kImage).status, RoiStatus::Inside);
  // 60 m ahead the ROI is 500·0.64/59.5 ≈ 5.4 px tall: seen, but too small to judge.
  EXPECT_EQ(projector.project(Vec3(60, 0, 0), kImage).status, RoiStatus::TooSmall);
  EXPECT_EQ(projector.project(Vec3(NAN, 0, 0), kImage).status, RoiStatus::Outside);
}

TEST(CameraProjection, AFrameOfAnotherResolutionIsScaled) {
  const ConeProjector projector(pinhole());
  const CandidateRoi full = projector.project(Vec3(8, 1, 0), kImage);
  const CandidateRoi half = projector.project(Vec3(8, 1, 0), cv::Size(320, 240));
  EXPECT_NEAR(half.base.x, full.base.x / 2, 1e-9);
  EXPECT_NEAR(half.base.y, full.base.y / 2, 1e-9);
  EXPECT_NEAR(half.box.height, full.box.height / 2, 1e-9);
}

TEST(CameraProjection, AutoPicksThePinholeOnlyWhenTheCalibrationHasIt) {
  EXPECT_TRUE(ConeProjector(pinhole()).pinhole());
  EXPECT_FALSE(ConeProjector(homography_only()).pinhole());
  CameraCalibration intrinsics_only;
  intrinsics_only.intrinsics = intrinsics();
  EXPECT_THROW(ConeProjector{intrinsics_only}, std::invalid_argument);
  ConeProjectionConfig want_pinhole;
  want_pinhole.model = "pinhole";
  EXPECT_THROW(ConeProjector(homography_only(), want_pinhole), std::invalid_argument);
  EXPECT_THROW(ConeProjector(CameraCalibration{}, homography_model()), std::invalid_argument);
}

}  // namespace
}  // namespace fsd
