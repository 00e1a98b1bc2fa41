#pragma once
// Camera stage 1 (DESIGN.md §5b, the paper's §III.B.1): a LiDAR cone candidate's ground position into the image,
// and the region of interest (ROI) the classifier and the colour stage look at. The ROI is the image of an upright
// rectangle standing at the candidate, facing the camera, as wide and tall as a cone with margins: its size in
// pixels follows the range.
//
// Two camera models, as the calibration allows (common/camera_geometry.hpp):
//   pinhole:    intrinsics (with lens distortion, cv::projectPoints) and the mount on the body: the rectangle's
//               corners are projected exactly.
//   homography: the paper's ground homography alone (`fsd calibrate-homography`): the base point maps through it,
//               the image scale at the cone is the pixel length of a ground segment across the line of sight, and the
//               ROI's height is that scale times the rectangle's height (square pixels, an upright camera).
// A frame of another size than the calibration's is handled by scaling pixels (same camera, other resolution).
#include <string>

#include <opencv2/core/types.hpp>

#include "common/camera_geometry.hpp"
#include "common/config.hpp"

namespace fsd {

struct ConeProjectionConfig {
  std::string model =
      "auto";  // auto (pinhole when intrinsics and extrinsics are known, else homography) | pinhole | homography
  double roi_width = 0.44;     // m: the big cone's 0.285 m base, LiDAR centroid error and a margin
  double roi_height = 0.58;    // m above the base point: the big cone's 0.505 m and a margin
  double roi_below = 0.06;     // m below the base point: base plate, ground height error
  double min_roi_pixels = 12;  // px: an ROI less tall than this (a far cone) is left unverified
  double min_inside = 0.75;    // share of the ROI's area inside the image, else the candidate is left unverified
};
const ConfigSection<ConeProjectionConfig>& cone_projection_section();  // prefix "perception.camera.projection"

enum class RoiStatus { Inside, Outside, TooSmall };

struct CandidateRoi {
  RoiStatus status = RoiStatus::Outside;
  cv::Rect2d box;       // the whole ROI in pixels; may reach past the image border
  cv::Rect pixels;      // whole pixels of `box` (outward-rounded), not cut to the image
  cv::Point2d base;     // pixel of the base point
  double px_per_m = 0;  // image scale at the candidate
};

class ConeProjector {
 public:
  // Throws std::invalid_argument when the calibration lacks what the model needs (pinhole: intrinsics and
  // extrinsics; homography: a homography) or the configuration is inconsistent.
  explicit ConeProjector(const CameraCalibration& calibration, const ConeProjectionConfig& cfg = {});

  // `ground`: the candidate's base point in the vehicle frame (z of the ground there; the homography ignores it).
  CandidateRoi project(const Vec3& ground, cv::Size image) const;
  bool pinhole() const { return pinhole_; }
  const ConeProjectionConfig& config() const { return cfg_; }

 private:
  bool project_pinhole(const Vec3& ground, cv::Size image, CandidateRoi& roi) const;
  bool project_homography(const Vec3& ground, cv::Size image, CandidateRoi& roi) const;
  cv::Point2d pixel_scale(cv::Size image) const;

  ConeProjectionConfig cfg_;
  CameraCalibration calibration_;
  bool pinhole_ = false;
  Pose3 optical_from_body_ = Pose3::Identity();
  Vec2 camera_ground_ = Vec2::Zero();  // the camera's position over the ground, for the line of sight
};

}  // namespace fsd
