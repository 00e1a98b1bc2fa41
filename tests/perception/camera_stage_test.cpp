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
#include "tests/perception/camera_painted_frame.hpp"

namespace fsd {
namespace {

using namespace test;  // the painted frame

TEST(CameraStage, AcceptedCandidatesGetStageCameraAndTheirColour) {
  cv::Mat frame = asphalt();
  const struct {
    double x, y;
    ConeColour colour;
  } cones[] = {{6, 1.5, ConeColour::Blue},
               {6, -1.5, ConeColour::Yellow},
               {9, 0.4, ConeColour::Orange},
               {11, -1.2, ConeColour::Red},
               {8, 2.6, ConeColour::Blue}};
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

// A timing line seen from behind: a yellow boundary cone 0.5 m behind a big orange one, nearly in line with the
// camera. Its ROI shows mostly the big cone: the stage neither verifies it nor names it (after the cone in front it
// would be orange) and leaves it the LiDAR's, unverified. Alone, at the same place, it is verified and yellow; a cone
// beside the big one, not behind it, keeps its colour.
TEST(CameraStage, ACandidateMostlyHiddenBehindANearerOneIsLeftToTheLidar) {
  cv::Mat frame = asphalt();
  paint(frame, 9.5, 1.5, ConeColour::Yellow);  // farther first: the nearer one is painted over it
  paint(frame, 9.0, 1.45, ConeColour::Orange, true);
  paint(frame, 9.5, -1.5, ConeColour::Blue);
  CameraStage stage(calibration(), constant_model(1.0));
  std::vector<Cone> seen{lidar_candidate(9.5, 1.5), lidar_candidate(9.0, 1.45), lidar_candidate(9.5, -1.5)};
  const std::vector<CandidateSize> sizes{{0.30, 0.22}, {0.49, 0.28}, {0.30, 0.22}};
  stage.verify(seen, frame, sizes);
  ASSERT_EQ(seen.size(), 3u);
  EXPECT_EQ(seen[0].stage, DetectionStage::Lidar);
  EXPECT_EQ(seen[0].colour, ConeColour::Unknown) << to_string(seen[0].colour);
  EXPECT_EQ(seen[1].stage, DetectionStage::Camera);
  EXPECT_EQ(seen[1].colour, ConeColour::BigOrange);
  EXPECT_EQ(seen[2].colour, ConeColour::Blue);
  EXPECT_EQ(stage.stats().hidden, 1u);
  EXPECT_EQ(stage.stats().verified, 2u);

  cv::Mat alone = asphalt();
  paint(alone, 9.5, 1.5, ConeColour::Yellow);
  std::vector<Cone> one{lidar_candidate(9.5, 1.5)};
  stage.verify(one, alone);
  EXPECT_EQ(one[0].stage, DetectionStage::Camera);
  EXPECT_EQ(one[0].colour, ConeColour::Yellow);
}

// Partly hidden (between a third and two thirds of its body behind a nearer cone of another colour), a cone gets
// its own colour from the part that shows: the nearer cone's pixels take no part in the vote.
TEST(CameraStage, APartlyHiddenCandidateGetsTheColourOfThePartThatShows) {
  for (const double offset : {0.05, 0.07, -0.12, -0.14}) {
    cv::Mat frame = asphalt();
    paint(frame, 9.5, 1.5, ConeColour::Yellow);  // farther first: the nearer one is painted over it
    paint(frame, 9.25, 1.5 + offset, ConeColour::Blue);
    CameraStage stage(calibration(), constant_model(1.0));
    std::vector<Cone> seen{lidar_candidate(9.5, 1.5), lidar_candidate(9.25, 1.5 + offset)};
    const std::vector<CandidateSize> sizes{{0.30, 0.22}, {0.30, 0.22}};
    const CandidateRoi far = stage.projector().project(seen[0].position, frame.size());
    const CandidateRoi near = stage.projector().project(seen[1].position, frame.size());
    const std::array<ImageSilhouette, 1> in_front{{{near.base, near.px_per_m, 0.11, 0.30}}};
    const double hidden = hidden_share(far.base, far.px_per_m, in_front);
    ASSERT_GT(hidden, 0.3) << offset;  // hidden enough that the whole ROI's colour would be in doubt
    ASSERT_LT(hidden, 0.7) << offset;
    stage.verify(seen, frame, sizes);
    ASSERT_EQ(seen.size(), 2u);
    EXPECT_EQ(seen[0].colour, ConeColour::Yellow) << offset << ": " << to_string(seen[0].colour);
    EXPECT_EQ(seen[1].colour, ConeColour::Blue) << offset;
    EXPECT_EQ(stage.stats().hidden, 0u);
  }
}

// A big orange cone of a timing line standing just behind and beside a small cone fills much of the small cone's
// ROI (its margins are a big cone's size, for the LiDAR's centroid error) with saturated orange: the small cone is
// still named by its own pixels, those on its base point, not by the taller one behind it.
TEST(CameraStage, ABigConeBehindASmallOneDoesNotNameIt) {
  for (const double beside : {0.25, -0.25, 0.32, -0.32}) {
    cv::Mat frame = asphalt();
    paint(frame, 6.5, 1.5 + beside, ConeColour::BigOrange, true);  // farther first: the small one stands in front
    paint(frame, 6.0, 1.5, ConeColour::Blue);
    CameraStage stage(calibration(), constant_model(1.0));
    std::vector<Cone> seen{lidar_candidate(6.0, 1.5), lidar_candidate(6.5, 1.5 + beside)};
    const std::vector<CandidateSize> sizes{{0.30, 0.22}, {0.49, 0.28}};
    stage.verify(seen, frame, sizes);
    ASSERT_EQ(seen.size(), 2u);
    EXPECT_EQ(seen[0].colour, ConeColour::Blue) << beside << ": " << to_string(seen[0].colour);
    EXPECT_EQ(seen[1].colour, ConeColour::BigOrange) << beside << ": " << to_string(seen[1].colour);
  }
}

}  // namespace
}  // namespace fsd
