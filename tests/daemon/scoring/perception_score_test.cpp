// The scorecard's perception section on one hand-made frame: the car's true pose places the detections, pairs
// are one to one within the gate, recall by range, colour within 12 m.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include <nlohmann/json.hpp>

#include "daemon/scoring/perception_score.hpp"
#include "tests/cone_at.hpp"

namespace fsd {
namespace {

const auto cone = test::cone_at;

TEST(PerceptionScore, PrecisionRecallByRangeErrorAndColour) {
  // The car at (10, 0) heading +y (vehicle x = map +y, vehicle y = map −x). True cones straight ahead at 5, 13,
  // 18 and 25 m.
  const Pose2 pose{10.0, 0.0, std::numbers::pi / 2};
  const std::vector<Cone> truth = {cone(10, 5, ConeColour::Blue), cone(10, 13, ConeColour::Yellow),
                                   cone(10, 18, ConeColour::Blue), cone(10, 25, ConeColour::Yellow)};
  ConeDetections det;
  det.cones = {cone(5, 0, ConeColour::Blue),      // the 5 m cone, exactly, right colour
               cone(13, -0.3, ConeColour::Blue),  // the 13 m cone 0.3 m to the car's right (map +x), wrong colour
               cone(8, 4, ConeColour::Yellow)};   // nothing there: a false positive
  PerceptionScore score;
  score.add_frame(det, truth, pose);
  const auto j = score.to_json();
  EXPECT_EQ(j["frames"], 1);
  EXPECT_EQ(j["detections"], 3);
  EXPECT_NEAR(j["precision"].get<double>(), 2.0 / 3.0, 5e-5);
  EXPECT_NEAR(j["recall_15m"].get<double>(), 1.0, 5e-5);        // 5 and 13 m: both found
  EXPECT_NEAR(j["recall_20m"].get<double>(), 2.0 / 3.0, 5e-5);  // 18 m missed; 25 m does not count
  EXPECT_NEAR(j["position_rmse_m"].get<double>(), std::sqrt((0.0 + 0.09) / 2.0), 5e-5);
  EXPECT_NEAR(j["colour_accuracy_12m"].get<double>(), 1.0, 1e-12);  // the wrong colour is at 13 m
}

TEST(PerceptionScore, ColourByStageAndRange) {
  // The car at the origin heading +x. Cones at 4 m (blue, coloured by reflectivity), 8 m (yellow, verified by the
  // camera, right), 10 m (blue, verified, named wrong), 11 m (yellow, unverified, unknown).
  const std::vector<Cone> truth = {cone(4, 1, ConeColour::Blue), cone(8, -1, ConeColour::Yellow),
                                   cone(10, 1, ConeColour::Blue), cone(11, -1, ConeColour::Yellow)};
  ConeDetections det;
  det.cones = {cone(4, 1, ConeColour::Blue), cone(8, -1, ConeColour::Yellow), cone(10, 1, ConeColour::Yellow),
               cone(11, -1, ConeColour::Unknown)};
  det.cones[0].stage = DetectionStage::Lidar;
  det.cones[1].stage = det.cones[2].stage = DetectionStage::Camera;
  det.cones[3].stage = DetectionStage::Lidar;
  PerceptionScore score;
  score.add_frame(det, truth, Pose2{});
  const auto j = score.to_json();
  EXPECT_NEAR(j["colour_accuracy_12m"].get<double>(), 0.5, 1e-12);             // 2 of 4
  EXPECT_NEAR(j["verified_share_12m"].get<double>(), 0.5, 1e-12);              // 8 and 10 m
  EXPECT_NEAR(j["verified_colour_accuracy_12m"].get<double>(), 0.5, 1e-12);    // 8 right, 10 wrong
  EXPECT_NEAR(j["named_colour_accuracy_12m"].get<double>(), 2.0 / 3.0, 1e-4);  // the unknown is not named
  EXPECT_NEAR(j["colour_accuracy_6m"].get<double>(), 1.0, 1e-12);              // only the 4 m cone
}

TEST(PerceptionScore, FramesAccumulateAndNothingSeenIsZeroNotNaN) {
  PerceptionScore score;
  score.add_frame({}, {cone(3, 0, ConeColour::Blue)}, Pose2{});
  auto j = score.to_json();
  EXPECT_EQ(j["precision"], 0.0);
  EXPECT_EQ(j["recall_15m"], 0.0);
  EXPECT_EQ(j["position_rmse_m"], 0.0);
  ConeDetections det;
  det.cones = {cone(3, 0, ConeColour::Blue)};
  score.add_frame(det, {cone(3, 0, ConeColour::Blue)}, Pose2{});
  j = score.to_json();
  EXPECT_EQ(j["frames"], 2);
  EXPECT_EQ(j["precision"], 1.0);
  EXPECT_EQ(j["recall_15m"], 0.5);
}

}  // namespace
}  // namespace fsd
