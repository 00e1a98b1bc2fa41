#include "perception/camera/cone_projection.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <vector>

#include <opencv2/calib3d.hpp>

namespace fsd {

const ConfigSection<ConeProjectionConfig>& cone_projection_section() {
  static const auto s =
      ConfigSection<ConeProjectionConfig>("perception.camera.projection")
          .string("model", &ConeProjectionConfig::model, {"auto", "pinhole", "homography"},
                  "How candidates are projected into the image: pinhole (intrinsics, distortion and mount of the "
                  "calibration file), homography (the paper's ground homography alone), auto = pinhole when the "
                  "calibration has intrinsics and extrinsics, else homography.")
          .number("roi_width", &ConeProjectionConfig::roi_width, 0.1, 2.0, "m",
                  "Width of the ROI at the candidate: a big cone's 0.285 m base with margin for the LiDAR centroid.")
          .number("roi_height", &ConeProjectionConfig::roi_height, 0.1, 2.0, "m",
                  "Height of the ROI above the candidate's base point (the big cone is 0.505 m).")
          .number("roi_below", &ConeProjectionConfig::roi_below, 0.0, 0.5, "m",
                  "The ROI reaches this far below the base point (base plate, ground height error).")
          .number("min_roi_pixels", &ConeProjectionConfig::min_roi_pixels, 4.0, 200.0, "px",
                  "Candidates whose ROI is less tall than this (far away) are left unverified.")
          .number("min_inside", &ConeProjectionConfig::min_inside, 0.1, 1.0, "",
                  "Share of the ROI that must lie inside the image; candidates with less are left unverified.");
  return s;
}

namespace {
constexpr double kMinDepth = 0.1;       // m in front of the optical centre
constexpr double kFieldMargin = 0.5;    // normalised coordinates this far past the image edges are not projected
constexpr double kMinSightline = 0.05;  // m: a candidate under the camera has no line of sight

bool has_pinhole(const CameraCalibration& c) { return c.intrinsics.has_value() && c.extrinsics.has_value(); }

cv::Rect outward(const cv::Rect2d& b) {
  const int x0 = static_cast<int>(std::floor(b.x)), y0 = static_cast<int>(std::floor(b.y));
  const int x1 = static_cast<int>(std::ceil(b.x + b.width)), y1 = static_cast<int>(std::ceil(b.y + b.height));
  return {x0, y0, x1 - x0, y1 - y0};
}
}  // namespace

ConeProjector::ConeProjector(const CameraCalibration& calibration, const ConeProjectionConfig& cfg)
    : cfg_(cfg), calibration_(calibration) {
  if (cfg_.model == "pinhole" || (cfg_.model == "auto" && has_pinhole(calibration))) {
    if (!has_pinhole(calibration))
      throw std::invalid_argument("camera projection 'pinhole' needs the calibration's intrinsics and extrinsics");
    pinhole_ = true;
  } else if (cfg_.model == "homography" || cfg_.model == "auto") {
    if (!calibration.homography)
      throw std::invalid_argument(
          "camera projection needs a calibration with intrinsics and extrinsics or a ground homography "
          "(fsd calibrate-homography)");
  } else {
    throw std::invalid_argument("camera projection model '" + cfg_.model + "' is not auto, pinhole or homography");
  }
  if (!(cfg_.roi_width > 0) || !(cfg_.roi_height > 0) || !(cfg_.roi_below >= 0))
    throw std::invalid_argument("camera projection: the ROI needs a positive width and height");
  if (calibration.extrinsics) {
    const Pose3 body_from_optical = calibration.extrinsics->body_from_optical();
    optical_from_body_ = body_from_optical.inverse();
    camera_ground_ = body_from_optical.translation().head<2>();
  }
}

cv::Point2d ConeProjector::pixel_scale(cv::Size image) const {
  if (!calibration_.intrinsics) return {1.0, 1.0};
  return {static_cast<double>(image.width) / calibration_.intrinsics->width,
          static_cast<double>(image.height) / calibration_.intrinsics->height};
}

CandidateRoi ConeProjector::project(const Vec3& ground, cv::Size image) const {
  CandidateRoi roi;
  if (!ground.allFinite() || image.width <= 0 || image.height <= 0) return roi;
  const bool ok = pinhole_ ? project_pinhole(ground, image, roi) : project_homography(ground, image, roi);
  if (!ok || !(roi.box.area() > 0)) return roi;
  roi.pixels = outward(roi.box);
  const cv::Rect2d inside = roi.box & cv::Rect2d(-0.5, -0.5, image.width, image.height);
  if (inside.area() < cfg_.min_inside * roi.box.area()) return roi;
  roi.status = roi.box.height < cfg_.min_roi_pixels ? RoiStatus::TooSmall : RoiStatus::Inside;
  return roi;
}

bool ConeProjector::project_pinhole(const Vec3& ground, cv::Size image, CandidateRoi& roi) const {
  const CameraIntrinsics& in = *calibration_.intrinsics;
  const Vec2 sight = ground.head<2>() - camera_ground_;
  if (sight.norm() < kMinSightline) return false;
  const Vec3 across = Vec3(-sight.y(), sight.x(), 0.0).normalized() * (cfg_.roi_width / 2);
  const Vec3 low = ground - Vec3(0, 0, cfg_.roi_below), high = ground + Vec3(0, 0, cfg_.roi_height);
  const std::array<Vec3, 5> body{ground, low + across, low - across, high + across, high - across};

  // Normalised image coordinates of the undistorted image's extent, widened so that corners a little outside still
  // project (the distortion polynomial is only meaningful near the field of view).
  const double fx = in.K(0, 0), fy = in.K(1, 1), cx = in.K(0, 2), cy = in.K(1, 2);
  const double x_lo = (-cx) / fx - kFieldMargin * in.width / fx,
               x_hi = (in.width - cx) / fx + kFieldMargin * in.width / fx;
  const double y_lo = (-cy) / fy - kFieldMargin * in.height / fy,
               y_hi = (in.height - cy) / fy + kFieldMargin * in.height / fy;
  std::vector<cv::Point3d> optical;
  for (const Vec3& p : body) {
    const Vec3 q = optical_from_body_ * p;
    if (q.z() < kMinDepth) return false;
    const double xn = q.x() / q.z(), yn = q.y() / q.z();
    if (xn < x_lo || xn > x_hi || yn < y_lo || yn > y_hi) return false;
    optical.emplace_back(q.x(), q.y(), q.z());
  }
  cv::Matx33d K;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) K(r, c) = in.K(r, c);
  std::vector<cv::Point2d> px;
  cv::projectPoints(optical, cv::Vec3d::all(0), cv::Vec3d::all(0), K, in.distortion, px);
  const cv::Point2d scale = pixel_scale(image);
  for (auto& p : px) p = {p.x * scale.x, p.y * scale.y};
  roi.base = px[0];
  double u0 = px[1].x, u1 = px[1].x, v0 = px[1].y, v1 = px[1].y;
  for (std::size_t i = 2; i < px.size(); ++i) {
    u0 = std::min(u0, px[i].x), u1 = std::max(u1, px[i].x);
    v0 = std::min(v0, px[i].y), v1 = std::max(v1, px[i].y);
  }
  roi.box = cv::Rect2d(u0, v0, u1 - u0, v1 - v0);
  roi.px_per_m = roi.box.height / (cfg_.roi_height + cfg_.roi_below);
  return std::isfinite(roi.px_per_m);
}

bool ConeProjector::project_homography(const Vec3& ground, cv::Size image, CandidateRoi& roi) const {
  const GroundHomography& h = calibration_.homography->homography;
  const Vec2 g = ground.head<2>();
  const Vec2 sight = g - camera_ground_;
  if (sight.norm() < kMinSightline) return false;
  const Vec2 across = Vec2(-sight.y(), sight.x()).normalized() * (cfg_.roi_width / 2);
  const auto base = ground_to_image(h, g), left = ground_to_image(h, g + across),
             right = ground_to_image(h, g - across);
  if (!base || !left || !right) return false;
  const cv::Point2d scale = pixel_scale(image);
  const auto px = [&](const Vec2& p) { return cv::Point2d(p.x() * scale.x, p.y() * scale.y); };
  roi.base = px(*base);
  roi.px_per_m = cv::norm(px(*left) - px(*right)) / cfg_.roi_width;
  if (!std::isfinite(roi.px_per_m) || !std::isfinite(roi.base.x) || !std::isfinite(roi.base.y)) return false;
  const double w = roi.px_per_m * cfg_.roi_width;
  roi.box = cv::Rect2d(roi.base.x - w / 2, roi.base.y - roi.px_per_m * cfg_.roi_height, w,
                       roi.px_per_m * (cfg_.roi_height + cfg_.roi_below));
  return true;
}

}  // namespace fsd
