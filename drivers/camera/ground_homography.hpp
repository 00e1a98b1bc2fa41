#pragma once
// The paper's joint calibration of camera and LiDAR (§III.B.1): a perspective transform between the image and the
// vehicle's ground plane, from exactly four image ↔ ground point pairs (cv::getPerspectiveTransform). Ground points
// are in the vehicle frame on the ground (x forward, y left, metres); pixels are OpenCV image coordinates (u right,
// v down, pixel centres at integers). The paper maps the bottom centre of a cone in the image to its position on
// the ground, and a LiDAR cluster's ground position back into the image to cut the ROI the classifier looks at.
//
// A homography is defined up to scale; this one is scaled so that the homogeneous w is positive for points in front
// of the camera. Pixels at or above the horizon and ground points behind the camera have no image: the mapping
// functions then return nothing.
#include <array>
#include <optional>
#include <stdexcept>
#include <string>

#include <opencv2/core/matx.hpp>
#include <opencv2/core/types.hpp>

#include "common/geometry.hpp"

namespace fsd {

using PointQuad = std::array<cv::Point2d, 4>;

// Thrown for point sets or matrices that cannot define a ground homography; what() names the problem.
class HomographyError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

struct GroundHomography {
  cv::Matx33d image_to_ground = cv::Matx33d::eye();
  cv::Matx33d ground_to_image = cv::Matx33d::eye();
};

// From four pairs (image_points[i] ↔ ground_points[i]). Throws HomographyError when a coordinate is not finite,
// when three points of either set are (nearly) collinear (which includes repeated points), or when the two
// quadrilaterals cannot be views of each other (the points are in a different order, so the horizon would cross them).
GroundHomography compute_ground_homography(const PointQuad& image_points, const PointQuad& ground_points);

// From a stored image → ground matrix: checks that it is finite and invertible and derives the inverse.
GroundHomography make_ground_homography(const cv::Matx33d& image_to_ground);

// The homography of an ideal pinhole camera (no distortion) with intrinsics K and pose body ← optical frame
// (x right, y down, z forward) over the ground plane z = 0 of the body frame.
GroundHomography pinhole_ground_homography(const cv::Matx33d& K, const Pose3& body_from_optical);

std::optional<cv::Point2d> image_to_ground(const GroundHomography& h, const cv::Point2d& pixel);
std::optional<cv::Point2d> ground_to_image(const GroundHomography& h, const cv::Point2d& ground);

// Parses exactly four points written "a1,b1;a2,b2;a3,b3;a4,b4" (spaces allowed). Throws HomographyError naming
// `what` and the bad part.
PointQuad parse_point_quad(const std::string& text, const std::string& what);

}  // namespace fsd
