#pragma once
// A hand-painted camera frame for the camera-stage tests: a pinhole camera written out here (not the stage's
// projection), cones painted where it sees them on plain asphalt, and LiDAR candidates at their ground positions.
#include <array>
#include <cmath>

#include <opencv2/imgproc.hpp>

#include "common/camera_geometry.hpp"
#include "common/types.hpp"
#include "perception/camera/cone_classifier.hpp"
#include "tests/perception/camera_drawn_cone.hpp"

namespace fsd::test {

// Camera 1.2 m up, 0.5 m ahead of the rear axle, pitched 0.15 rad down, f = 500 px, 640 × 480.
constexpr double kF = 500, kCx = 320, kCy = 240, kMountX = 0.5, kHeight = 1.2, kPitch = 0.15;

struct Seen {
  cv::Point2d pixel;
  double depth;
};
inline Seen see(double X, double Y, double Z) {
  const double c = std::cos(kPitch), s = std::sin(kPitch);
  const double dx = X - kMountX, dy = Y, dz = Z - kHeight;
  const double depth = c * dx - s * dz;
  return {{kCx + kF * (-dy) / depth, kCy + kF * (-(s * dx + c * dz)) / depth}, depth};
}

inline CameraCalibration calibration() {
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
inline ConeClassifierModel constant_model(double score) {
  ConeClassifierModel m;
  m.weights.assign(m.hog.descriptor_size(), 0.0);
  m.bias = score;
  return m;
}

// Paints a cone standing at ground (X, Y): body as a trapezoid from its base to its tip, with its stripe bands.
inline void paint(cv::Mat& frame, double X, double Y, ConeColour colour, bool big = false) {
  cv::RNG rng(static_cast<std::uint64_t>(X * 100 + Y * 10 + 1000));
  DrawnCone d;
  paint_cone(d, big ? ConeColour::BigOrange : colour, rng);
  const double height = big ? 0.505 : 0.325, r0 = big ? 0.1425 : 0.114, r1 = 0.025;
  const int bands = 40;
  for (int k = 0; k < bands; ++k) {
    const double z0 = height * k / bands, z1 = height * (k + 1) / bands, zm = (z0 + z1) / 2 / height;
    bool stripe = false;
    for (const auto& s : d.stripes) stripe = stripe || (zm >= s[0] && zm < s[1]);
    const double ra = r0 + (r1 - r0) * z0 / height, rb = r0 + (r1 - r0) * z1 / height;
    const std::array<Seen, 4> q{see(X, Y + ra, z0), see(X, Y - ra, z0), see(X, Y - rb, z1), see(X, Y + rb, z1)};
    std::array<cv::Point, 4> pts;
    for (std::size_t i = 0; i < 4; ++i)
      pts[i] = cv::Point(static_cast<int>(q[i].pixel.x * 16), static_cast<int>(q[i].pixel.y * 16));
    cv::fillConvexPoly(frame, pts.data(), 4, stripe ? d.stripe : d.body, cv::LINE_AA, 4);
  }
}

inline cv::Mat asphalt() {
  cv::Mat frame(480, 640, CV_8UC3, cv::Scalar(95, 95, 98));
  cv::Mat noise(frame.size(), CV_8UC3);
  cv::RNG(1).fill(noise, cv::RNG::NORMAL, 0, 3);
  frame += noise;
  return frame;
}

inline Cone lidar_candidate(double x, double y) {
  Cone c;
  c.position = Vec3(x, y, 0);
  c.stage = DetectionStage::Lidar;
  c.colour = ConeColour::Unknown;
  c.colour_source = ColourSource::None;
  c.colour_confidence = 0;
  c.points = 12;
  return c;
}

}  // namespace fsd::test
