// CameraStage::verify, the contract with the LiDAR stages: on a frame with cones painted by hand where a pinhole
// camera (projection written out here) sees them, accepted candidates get stage Camera and their colour, rejected
// ones are removed and counted, those the camera cannot see and every candidate of an unusable frame stay as the
// LiDAR gave them.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <stdexcept>

#include <opencv2/imgproc.hpp>

#include "perception/camera/camera_stage.hpp"
#include "tests/perception/camera_drawn_cone.hpp"

namespace fsd {
namespace {

// Camera 1.2 m up, 0.5 m ahead of the rear axle, pitched 0.15 rad down, f = 500 px, 640 × 480.
constexpr double kF = 500, kCx = 320, kCy = 240, kMountX = 0.5, kHeight = 1.2, kPitch = 0.15;

struct Seen {
  cv::Point2d pixel;
  double depth;
};
Seen see(double X, double Y, double Z) {
  const double c = std::cos(kPitch), s = std::sin(kPitch);
  const double dx = X - kMountX, dy = Y, dz = Z - kHeight;
  const double depth = c * dx - s * dz;
  return {{kCx + kF * (-dy) / depth, kCy + kF * (-(s * dx + c * dz)) / depth}, depth};
}

CameraCalibration calibration() {
  CameraCalibration c;
  CameraIntrinsics in;
  in.width = 640;
  in.height = 480;
  in.K << kF, 0, kCx, 0, kF, kCy, 0, 0, 1;
  c.intrinsics = in;
  c.extrinsics = CameraMount{kMountX, 0, kHeight, 0, kPitch, 0};
  return c;
}

// A model whose decision is the same for every ROI: all weights 0, the bias the score.
ConeClassifierModel constant_model(double score) {
  ConeClassifierModel m;
  m.weights.assign(m.hog.descriptor_size(), 0.0);
  m.bias = score;
  return m;
}

// Paints a cone standing at ground (X, Y): body as a trapezoid from its base to its tip, with its stripe bands.
void paint(cv::Mat& frame, double X, double Y, ConeColour colour, bool big = false) {
  cv::RNG rng(static_cast<std::uint64_t>(X * 100 + Y * 10 + 1000));
  test::DrawnCone d;
  test::paint_cone(d, big ? ConeColour::BigOrange : colour, rng);
  const double height = big ? 0.505 : 0.325, r0 = big ? 0.1425 : 0.114, r1 = 0.025;
  const int bands = 40;
  for (int k = 0; k < bands; ++k) {
    const double z0 = height * k / bands, z1 = height * (k + 1) / bands, zm = (z0 + z1) / 2 / height;
    bool stripe = false;
    for (const auto& s : d.stripes) stripe = stripe || (zm >= s[0] && zm < s[1]);
    const double ra = r0 + (r1 - r0) * z0 / height, rb = r0 + (r1 - r0) * z1 / height;
    const std::array<Seen, 4> q{see(X, Y + ra, z0), see(X, Y - ra, z0), see(X, Y - rb, z1), see(X, Y + rb, z1)};
    std::array<cv::Point, 4> pts;
    for (std::size_t i = 0; i < 4; ++i) pts[i] = cv::Point(static_cast<int>(q[i].pixel.x * 16), static_cast<int>(q[i].pixel.y * 16));
    cv::fillConvexPoly(frame, pts.data(), 4, stripe ? d.stripe : d.body, cv::LINE_AA, 4);
  }
}

cv::Mat asphalt() {
  cv::Mat frame(480, 640, CV_8UC3, cv::Scalar(95, 95, 98));
  cv::Mat noise(frame.size(), CV_8UC3);
  cv::RNG(1).fill(noise, cv::RNG::NORMAL, 0, 3);
  frame += noise;
  return frame;
}

Cone lidar_candidate(double x, double y) {
  Cone c;
  c.position = Vec3(x, y, 0);
  c.stage = DetectionStage::Lidar;
  c.colour = ConeColour::Unknown;
  c.colour_source = ColourSource::None;
  c.colour_confidence = 0;
  c.points = 12;
  return c;
}

TEST(CameraStage, AcceptedCandidatesGetStageCameraAndTheirColour) {
  cv::Mat frame = asphalt();
  const struct {
    double x, y;
    ConeColour colour;
  } cones[] = {{6, 1.5, ConeColour::Blue}, {6, -1.5, ConeColour::Yellow}, {9, 0.4, ConeColour::Orange},
               {11, -1.2, ConeColour::Red}, {8, 2.6, ConeColour::Blue}};
  std::vector<Cone> candidates;
  for (const auto& c : cones) {
    paint(frame, c.x, c.y, c.colour);
    candidates.push_back(lidar_candidate(c.x, c.y));
  }
  candidates.push_back(lidar_candidate(-2, 0));  // behind the camera
  candidates.push_back(lidar_candidate(60, 0));  // too far to judge
  Cone truth = lidar_candidate(7, 0);
  truth.stage = DetectionStage::Truth;  // not a LiDAR candidate: passes through
  candidates.push_back(truth);

  CameraStage stage(calibration(), constant_model(1.0));
  const CameraFrameResult r = stage.verify(candidates, frame);
  EXPECT_TRUE(r.frame_ok);
  EXPECT_EQ(r.verified, 5);
  EXPECT_EQ(r.unverified, 2);
  ASSERT_EQ(candidates.size(), 8u);
  for (std::size_t i = 0; i < 5; ++i) {
    EXPECT_EQ(candidates[i].stage, DetectionStage::Camera) << i;
    EXPECT_EQ(candidates[i].colour, cones[i].colour) << i << ": " << to_string(candidates[i].colour);
    EXPECT_EQ(candidates[i].colour_source, ColourSource::Camera);
    EXPECT_GE(candidates[i].colour_confidence, 0.55);
    EXPECT_EQ(candidates[i].position, Vec3(cones[i].x, cones[i].y, 0));  // the LiDAR's position is kept
    EXPECT_EQ(candidates[i].points, 12u);
  }
  for (std::size_t i = 5; i < 7; ++i) {
    EXPECT_EQ(candidates[i].stage, DetectionStage::Lidar) << i;
    EXPECT_EQ(candidates[i].colour_source, ColourSource::None) << i;
  }
  EXPECT_EQ(candidates[7].stage, DetectionStage::Truth);
  const CameraStageStats& s = stage.stats();
  EXPECT_EQ(s.frames, 1u);
  EXPECT_EQ(s.candidates, 7u);
  EXPECT_EQ(s.verified, 5u);
  EXPECT_EQ(s.outside, 1u);
  EXPECT_EQ(s.too_small, 1u);
  EXPECT_EQ(s.rejected, 0u);
}

TEST(CameraStage, RejectedCandidatesAreRemovedAndCounted) {
  std::vector<Cone> candidates{lidar_candidate(6, 1), lidar_candidate(-5, 0), lidar_candidate(8, -1)};
  CameraStage stage(calibration(), constant_model(-1.0));
  const CameraFrameResult r = stage.verify(candidates, asphalt());
  EXPECT_EQ(r.rejected, 2);
  ASSERT_EQ(candidates.size(), 1u);
  EXPECT_EQ(candidates[0].position.x(), -5);  // the one behind the camera stays, unverified
  EXPECT_EQ(candidates[0].stage, DetectionStage::Lidar);
  EXPECT_EQ(stage.stats().rejected, 2u);
}

TEST(CameraStage, AnUnusableFrameLeavesEveryCandidateAsItWas) {
  CameraStage stage(calibration(), constant_model(-1.0));
  for (const cv::Mat& bad : {cv::Mat(), cv::Mat(480, 640, CV_8UC1, cv::Scalar(0)), cv::Mat(1, 1, CV_8UC3)}) {
    std::vector<Cone> candidates{lidar_candidate(6, 1), lidar_candidate(8, -1)};
    const CameraFrameResult r = stage.verify(candidates, bad);
    EXPECT_FALSE(r.frame_ok);
    ASSERT_EQ(candidates.size(), 2u);
    EXPECT_EQ(candidates[0].stage, DetectionStage::Lidar);
  }
  EXPECT_EQ(stage.stats().bad_frames, 3u);
  EXPECT_EQ(stage.stats().candidates, 0u);
}

TEST(CameraStage, SizesMustMatchTheCandidates) {
  CameraStage stage(calibration(), constant_model(1.0));
  std::vector<Cone> candidates{lidar_candidate(6, 1)};
  const std::vector<CandidateSize> sizes(2);
  EXPECT_THROW(stage.verify(candidates, asphalt(), sizes), std::invalid_argument);
}

// Big orange from the cone's size: the LiDAR's height when given, else the painted height at the projected scale.
TEST(CameraStage, BigOrangeFromTheLidarHeightOrTheImage) {
  cv::Mat frame = asphalt();
  paint(frame, 6, 1.0, ConeColour::Orange);
  paint(frame, 6, -1.0, ConeColour::Orange, true);
  CameraStage stage(calibration(), constant_model(1.0));
  std::vector<Cone> seen{lidar_candidate(6, 1.0), lidar_candidate(6, -1.0)};
  stage.verify(seen, frame);
  EXPECT_EQ(seen[0].colour, ConeColour::Orange);
  EXPECT_EQ(seen[1].colour, ConeColour::BigOrange);
  std::vector<Cone> told{lidar_candidate(6, 1.0), lidar_candidate(6, -1.0)};
  const std::vector<CandidateSize> sizes{{0.49, 0.28}, {0.30, 0.22}};  // the LiDAR's envelope decides
  stage.verify(told, frame, sizes);
  EXPECT_EQ(told[0].colour, ConeColour::BigOrange);
  EXPECT_EQ(told[1].colour, ConeColour::Orange);
}

}  // namespace
}  // namespace fsd
