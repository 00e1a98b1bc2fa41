// Camera model colours: cone pixels keep the hue of their paint under dim warm and bright cool light, after JPEG
// compression, sensor noise and blur, so that an HSV classifier that ignores V works (the paper's §III.B.3).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include <opencv2/imgcodecs.hpp>

#include "tests/sim/camera_test_util.hpp"
#include "tests/sim/world_test_util.hpp"

namespace fsd::sim {
namespace {

using test::make_cone;
using test::make_track;

struct Patch {
  int hue;         // median OpenCV hue, 0..180
  int saturation;  // median
};

// Median hue and saturation of a 3×3 patch on the front of a small cone standing at (x, y), in its lower body band
// (8 cm above the ground: below the stripe on every cone), computed with the plain camera's projection by hand.
Patch lower_body_patch(const cv::Mat& bgr, double x, double y) {
  const double z = 0.08;
  const double radius = 0.114 - (0.114 - 0.025) * z / 0.325;
  const double front = x - radius;
  const int u = static_cast<int>(std::lround(319.5 - 400.0 * y / front));
  const int v = static_cast<int>(std::lround(239.5 + 400.0 * (1.0 - z) / front));
  cv::Mat hsv;
  cv::cvtColor(bgr(cv::Rect(u - 1, v - 1, 3, 3)), hsv, cv::COLOR_BGR2HSV);
  std::vector<int> h, s;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) {
      h.push_back(hsv.at<cv::Vec3b>(r, c)[0]);
      s.push_back(hsv.at<cv::Vec3b>(r, c)[1]);
    }
  std::nth_element(h.begin(), h.begin() + 4, h.end());
  std::nth_element(s.begin(), s.begin() + 4, s.end());
  return {h[4], s[4]};
}

// One frame as the driver would receive it: rendered, JPEG-encoded and decoded.
cv::Mat captured_frame(const CameraConfig& cfg, const World& world) {
  CameraModel cam(cfg, world, 7);
  cv::Mat decoded;
  cam.advance_to(
      0.0, [](Stamp) { return Pose3::Identity(); },
      [&](Stamp, std::span<const std::uint8_t> bytes) {
        decoded = cv::imdecode(std::vector<std::uint8_t>(bytes.begin(), bytes.end()), cv::IMREAD_COLOR);
      });
  return decoded;
}

TEST(CameraModelColour, ConeHuesStayInTheirBandsUnderLightChanges) {
  // Blue, yellow and orange cones side by side 6 m ahead.
  const World world(make_track({make_cone(6.0, 1.2, ConeRole::Left), make_cone(6.0, 0.0, ConeRole::Right),
                                make_cone(6.0, -1.2, ConeRole::Other)}),
                    test::bare_config(), 1);
  CameraConfig dim_warm = test::plain_camera();
  dim_warm.gain = 0.6;
  dim_warm.white_balance = 0.1;
  dim_warm.pixel_noise = 2.0;
  dim_warm.blur = 0.6;
  CameraConfig bright_cool = dim_warm;
  bright_cool.gain = 1.4;
  bright_cool.white_balance = -0.1;

  // Hue bands of OpenCV's 0..180 scale: orange ≈ 10, yellow ≈ 25, blue ≈ 110.
  for (const CameraConfig& cfg : {dim_warm, bright_cool}) {
    SCOPED_TRACE(cfg.gain < 1.0 ? "dim warm light" : "bright cool light");
    const cv::Mat img = captured_frame(cfg, world);
    ASSERT_EQ(img.size(), cv::Size(640, 480));
    const Patch blue = lower_body_patch(img, 6.0, 1.2);
    const Patch yellow = lower_body_patch(img, 6.0, 0.0);
    const Patch orange = lower_body_patch(img, 6.0, -1.2);
    EXPECT_GE(blue.hue, 100);
    EXPECT_LE(blue.hue, 130);
    EXPECT_GE(yellow.hue, 20);
    EXPECT_LE(yellow.hue, 35);
    EXPECT_LE(orange.hue, 17);
    for (const Patch& p : {blue, yellow, orange}) EXPECT_GT(p.saturation, 120);
  }
}

TEST(CameraModelColour, ExposureScalesBrightnessNotHue) {
  const World world(make_track({make_cone(6.0, 0.0, ConeRole::Right)}), test::bare_config(), 1);
  CameraConfig dim = test::plain_camera();
  dim.gain = 0.5;
  CameraConfig bright = dim;
  bright.gain = 1.0;
  const cv::Mat a = CameraModel(dim, world, 1).render(Pose3::Identity());
  const cv::Mat b = CameraModel(bright, world, 1).render(Pose3::Identity());
  // A pixel of asphalt near the bottom of the image: twice the gain, twice the value (within rounding).
  const cv::Vec3b ga = a.at<cv::Vec3b>(470, 320), gb = b.at<cv::Vec3b>(470, 320);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(gb[c], 2.0 * ga[c], 2.0);
}

TEST(CameraModelColour, LightingDriftsOverTimeWithinItsBounds) {
  CameraConfig cfg = test::plain_camera();
  cfg.gain_variation = 0.2;
  cfg.white_balance_variation = 0.05;
  cfg.light_event_probability = 0.5;
  cfg.light_event_depth = 0.35;
  double lo = 10, hi = 0, wb_lo = 1, wb_hi = -1;
  for (int i = 0; i < 4000; ++i) {
    const Exposure e = exposure_at(cfg, 3, i * 0.05);
    lo = std::min(lo, e.gain);
    hi = std::max(hi, e.gain);
    wb_lo = std::min(wb_lo, e.white_balance);
    wb_hi = std::max(wb_hi, e.white_balance);
  }
  // Gain within (1 ± 0.2)·(1 − 0.35 .. 1 + 0.175), and it does move; white balance within ±0.05.
  EXPECT_GE(lo, 0.8 * 0.65 - 1e-9);
  EXPECT_LE(hi, 1.2 * 1.175 + 1e-9);
  EXPECT_LT(lo, 0.85);
  EXPECT_GT(hi, 1.1);
  EXPECT_GE(wb_lo, -0.05 - 1e-9);
  EXPECT_LE(wb_hi, 0.05 + 1e-9);
  EXPECT_GT(wb_hi - wb_lo, 0.03);
  // Smooth: no jump of more than a few percent between frames 50 ms apart.
  for (int i = 1; i < 4000; ++i)
    EXPECT_LT(std::abs(exposure_at(cfg, 3, i * 0.05).gain - exposure_at(cfg, 3, (i - 1) * 0.05).gain), 0.05);
}

}  // namespace
}  // namespace fsd::sim
