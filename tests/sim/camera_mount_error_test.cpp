// sim.mismatch.camera_*: the virtual camera renders from a mount turned away from the one it reports (its
// calibration), as a camera knocked on the car. A cone 8 m straight ahead moves
// across the image by f·tan(yaw), and up by about f·pitch when the camera looks down.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <vector>

#include <opencv2/imgcodecs.hpp>

#include "drivers/sim/virtual_car.hpp"
#include "tests/sim/camera_test_util.hpp"
#include "tests/sim/world_test_util.hpp"

namespace fsd::sim {
namespace {

// The yellow cone's centroid (px) in the first frame, with the camera turned by `yaw` and `pitch` (rad).
cv::Point2d yellow_centroid(double yaw, double pitch) {
  Track track = test::make_track({test::make_cone(8.0, 0.0, ConeRole::Right)});
  track.start = Pose2(0, 0, 0);
  VirtualCarSettings s;
  s.run.lidar = s.run.gnss = false;
  s.world = test::bare_config();
  s.camera = test::plain_camera();
  s.camera_yaw_error = yaw;
  s.camera_pitch_error = pitch;
  std::optional<cv::Mat> frame;
  SensorSinks sinks;
  sinks.camera = [&](Stamp, std::span<const std::uint8_t> jpeg) {
    if (!frame) frame = cv::imdecode(std::vector<std::uint8_t>(jpeg.begin(), jpeg.end()), cv::IMREAD_COLOR);
  };
  VirtualCar car(track, s, 1, sinks);
  car.advance_to(0.2);
  EXPECT_TRUE(frame.has_value() && !frame->empty());
  if (!frame || frame->empty()) return {};
  const cv::Moments m = cv::moments(test::hue_mask(*frame, 20, 35), true);
  EXPECT_GT(m.m00, 50.0);
  return {m.m10 / m.m00, m.m01 / m.m00};
}

TEST(CameraMountError, TheImageTurnsWithTheCameraNotItsCalibration) {
  const cv::Point2d level = yellow_centroid(0.0, 0.0);
  EXPECT_NEAR(level.x, 319.5, 1.5);  // straight ahead, as the calibration (sim.camera) puts it
  // Turned 0.03 rad to the left: the cone moves right by 400·tan(0.03) = 12.0 px; pitched down: it moves up.
  const cv::Point2d yawed = yellow_centroid(0.03, 0.0);
  EXPECT_NEAR(yawed.x - level.x, 400.0 * std::tan(0.03), 1.0);
  EXPECT_NEAR(yawed.y, level.y, 1.0);
  const cv::Point2d pitched = yellow_centroid(0.0, 0.03);
  EXPECT_NEAR(pitched.x, level.x, 1.0);
  EXPECT_LT(pitched.y - level.y, -10.0);
}

}  // namespace
}  // namespace fsd::sim
