#pragma once
// Helpers of the camera model tests: a plain camera whose projection is easy to compute by hand, and colour
// thresholding of rendered images.
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "drivers/sim/sensors/camera_model.hpp"

namespace fsd::sim::test {

// Level camera 1 m above the rear axle, no lens effects, constant light: u = 319.5 − 400·y/x, v = 239.5 + 400·(1 − z)/x
// for a map point (x, y, z) seen from the body pose at the origin.
inline CameraConfig plain_camera() {
  CameraConfig c;
  c.width = 640;
  c.height = 480;
  c.fx = c.fy = 400.0;
  c.cx = 319.5;
  c.cy = 239.5;
  c.x = 0.0;
  c.y = 0.0;
  c.z = 1.0;
  c.roll = c.pitch = c.yaw = 0.0;
  c.pixel_noise = 0.0;
  c.blur = 0.0;
  c.gain_variation = 0.0;
  c.white_balance_variation = 0.0;
  c.light_event_probability = 0.0;
  return c;
}

// Pixels whose OpenCV hue (0..180) lies in [lo, hi] and whose saturation and value exceed the given floors.
inline cv::Mat hue_mask(const cv::Mat& bgr, int lo, int hi, int min_saturation = 100, int min_value = 40) {
  cv::Mat hsv, mask;
  cv::cvtColor(bgr, hsv, cv::COLOR_BGR2HSV);
  cv::inRange(hsv, cv::Scalar(lo, min_saturation, min_value), cv::Scalar(hi, 255, 255), mask);
  return mask;
}

}  // namespace fsd::sim::test
