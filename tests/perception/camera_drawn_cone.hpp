#pragma once
// Cone crops drawn by hand with OpenCV, for the colour and classifier tests: a cone of known colour (body and stripe
// paint in BGR), size, stripes, shading, lighting, colour cast and background, with sensor noise and blur. The truth
// is the paint the test chose, independent of the virtual car's renderer.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "common/types.hpp"

namespace fsd::test {

enum class Background { Asphalt, Grass, SkyAndAsphalt, Concrete, Gravel };

struct DrawnCone {
  cv::Size crop{60, 80};         // image size
  double fill = 0.85;            // cone height / crop height
  double centre = 0.5;           // cone axis at this share of the width
  double base = -1;              // base at this share of the height; < 0: the cone centred vertically
  double aspect = 0.70;          // base width / height (small cone 0.70, big 0.56)
  cv::Scalar body{200, 80, 30};  // BGR paint
  cv::Scalar stripe{240, 240, 240};
  std::vector<std::array<double, 2>> stripes{{0.38, 0.62}};  // height fractions from the base
  double light = 1.0;                                        // exposure
  cv::Scalar cast{1, 1, 1};                                  // per-channel white balance error (B, G, R)
  Background background = Background::Asphalt;
  double noise = 3.0;  // σ, 8-bit levels
  double blur = 0.7;   // σ, px
  std::uint64_t seed = 1;
};

inline cv::Scalar scaled(const cv::Scalar& c, double k) { return {c[0] * k, c[1] * k, c[2] * k}; }

inline cv::Mat draw_cone(const DrawnCone& d) {
  const int w = d.crop.width, h = d.crop.height;
  cv::Mat img(d.crop, CV_32FC3);
  cv::RNG rng(d.seed);
  // Background.
  const int horizon = static_cast<int>(0.3 * h);
  for (int r = 0; r < h; ++r) {
    cv::Scalar c;
    switch (d.background) {
      case Background::Asphalt:
        c = {95, 95, 98};
        break;
      case Background::Grass:
        c = {40, 140, 70};
        break;
      case Background::SkyAndAsphalt:
        c = r < horizon ? cv::Scalar(235, 190, 140) : cv::Scalar(90, 92, 95);
        break;
      case Background::Concrete:
        c = {165, 170, 172};
        break;
      case Background::Gravel:
        c = {110, 130, 150};
        break;
    }
    img.row(r).setTo(c);
  }
  cv::Mat mottling(std::max(2, h / 8), std::max(2, w / 8), CV_32FC1);
  rng.fill(mottling, cv::RNG::NORMAL, 1.0, 0.08);
  cv::resize(mottling, mottling, d.crop, 0, 0, cv::INTER_CUBIC);
  std::vector<cv::Mat> ch;
  cv::split(img, ch);
  for (auto& c : ch) c = c.mul(mottling);
  cv::merge(ch, img);

  // The cone: a trapezoid from the base to a narrow tip, bands of stripe paint, shaded across (sun from the left).
  const double H = d.fill * h, base_y = d.base >= 0 ? d.base * h : h - (h - H) / 2.0, cx = d.centre * w;
  const double r0 = d.aspect * H / 2, r1 = 0.08 * H;
  const int rows = d.fill > 0 ? std::max(1, static_cast<int>(std::ceil(H))) : 0;  // fill 0: background only
  for (int k = 0; k < rows; ++k) {
    const double z0 = static_cast<double>(k) / rows, z1 = static_cast<double>(k + 1) / rows;
    const double zm = (z0 + z1) / 2;
    bool in_stripe = false;
    for (const auto& s : d.stripes) in_stripe = in_stripe || (zm >= s[0] && zm < s[1]);
    const cv::Scalar paint = in_stripe ? d.stripe : d.body;
    const double ra = r0 + (r1 - r0) * z0, rb = r0 + (r1 - r0) * z1;
    const int slices = 8;
    for (int sl = 0; sl < slices; ++sl) {
      const double t0 = -1.0 + 2.0 * sl / slices, t1 = -1.0 + 2.0 * (sl + 1) / slices;
      const double shade = 1.05 - 0.35 * (t0 + t1) / 2;  // brighter on the left
      constexpr int kShift = 4, kOne = 1 << kShift;
      const auto P = [&](double x, double y) {
        return cv::Point(static_cast<int>(std::lround(x * kOne)), static_cast<int>(std::lround(y * kOne)));
      };
      const std::array<cv::Point, 4> quad{P(cx + t0 * ra, base_y - z0 * H), P(cx + t1 * ra, base_y - z0 * H),
                                          P(cx + t1 * rb, base_y - z1 * H), P(cx + t0 * rb, base_y - z1 * H)};
      cv::fillConvexPoly(img, quad.data(), 4, scaled(paint, shade), cv::LINE_AA, kShift);
    }
  }
  // Lighting, colour cast, optics, sensor.
  cv::multiply(img, cv::Scalar(d.light * d.cast[0], d.light * d.cast[1], d.light * d.cast[2]), img);
  if (d.blur > 0) cv::GaussianBlur(img, img, cv::Size(), d.blur);
  cv::Mat noise(d.crop, CV_32FC3);
  rng.fill(noise, cv::RNG::NORMAL, 0.0, d.noise);
  img += noise;
  cv::Mat out;
  img.convertTo(out, CV_8UC3);  // saturates at 0 and 255
  return out;
}

// Paint of the cones the rules use, in BGR, with a little variation by seed (real paints and cameras differ).
inline cv::Scalar paint_of(ConeColour c, cv::RNG& rng) {
  const auto j = [&](double v, double spread) { return std::clamp(v + rng.uniform(-spread, spread), 0.0, 255.0); };
  switch (c) {
    case ConeColour::Blue:
      return {j(175, 40), j(70, 30), j(20, 15)};
    case ConeColour::Yellow:
      return {j(20, 20), j(205, 15), j(235, 15)};
    case ConeColour::Orange:
    case ConeColour::BigOrange:
      return {j(15, 15), j(100, 25), j(245, 10)};
    case ConeColour::Red:
      return {j(40, 12), j(28, 10), j(200, 30)};  // crimson: green at most blue
    default:
      return {128, 128, 128};
  }
}

// The stripe paint and layout of each cone type: blue and orange white stripes, yellow black; the big cone two.
inline void paint_cone(DrawnCone& d, ConeColour c, cv::RNG& rng) {
  d.body = paint_of(c, rng);
  d.stripe = c == ConeColour::Yellow ? cv::Scalar(30, 30, 30) : cv::Scalar(235, 235, 235);
  if (c == ConeColour::BigOrange) {
    d.stripes = {{0.28, 0.40}, {0.58, 0.70}};
    d.aspect = 0.56;
  } else {
    d.stripes = {{0.38, 0.62}};
    d.aspect = 0.70;
  }
}

}  // namespace fsd::test
