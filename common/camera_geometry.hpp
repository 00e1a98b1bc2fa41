#pragma once
// The camera's geometry as calibration gives it (docs/camera.md): pinhole intrinsics, the mount on the vehicle, and
// the paper's ground homography (§III.B.1). Pure structs and math in Eigen, shared by the calibration file
// (drivers/camera/camera_calibration.hpp reads and writes them) and perception's projection stage; OpenCV types
// stay out of common/.
//
// Ground points are in the vehicle frame on the ground (x forward, y left, metres); pixels are image coordinates
// (u right, v down, pixel centres at integers).
#include <array>
#include <optional>
#include <stdexcept>
#include <vector>

#include "common/geometry.hpp"

namespace fsd {

using PointQuad = std::array<Vec2, 4>;

struct CameraIntrinsics {
  int width = 0, height = 0;  // image size the calibration belongs to
  Eigen::Matrix3d K = Eigen::Matrix3d::Identity();
  std::vector<double> distortion;  // OpenCV order (k1, k2, p1, p2[, k3[, k4, k5, k6[, s1..s4[, τx, τy]]]]), or empty
};

// Places the camera body frame (x forward, y left, z up; pitch positive looks down; Z-Y-X angles, rad) on the vehicle
// body frame (rear-axle centre on the ground, metres), like the LiDAR mount in the configuration.
struct CameraMount {
  double x = 0, y = 0, z = 0;
  double roll = 0, pitch = 0, yaw = 0;
  // Body ← optical frame (x right, y down, z forward).
  Pose3 body_from_optical() const;
};

// Thrown for point sets or matrices that cannot define a ground homography; what() names the problem.
class HomographyError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

// A perspective transform between the image and the vehicle's ground plane. A homography is defined up to scale;
// this one is scaled so that the homogeneous w is positive for points in front of the camera. Pixels at or above
// the horizon and ground points behind the camera have no image: the mapping functions then return nothing.
struct GroundHomography {
  Eigen::Matrix3d image_to_ground = Eigen::Matrix3d::Identity();
  Eigen::Matrix3d ground_to_image = Eigen::Matrix3d::Identity();
};

struct HomographyCalibration {
  GroundHomography homography;
  std::optional<PointQuad> image_points, ground_points;  // the pairs it was computed from, if known
};

// Every section is optional: a camera may be known by its homography alone (`fsd calibrate-homography`).
struct CameraCalibration {
  std::optional<CameraIntrinsics> intrinsics;
  std::optional<CameraMount> extrinsics;
  std::optional<HomographyCalibration> homography;
};

// From four pairs (image_points[i] ↔ ground_points[i]), the paper's four-point perspective transform. Throws
// HomographyError when a coordinate is not finite, when three points of either set are (nearly) collinear (which
// includes repeated points), or when the two quadrilaterals cannot be views of each other (the points are in a
// different order, so the horizon would cross them).
GroundHomography compute_ground_homography(const PointQuad& image_points, const PointQuad& ground_points);

// From a stored image → ground matrix: checks that it is finite and invertible and derives the inverse.
GroundHomography make_ground_homography(const Eigen::Matrix3d& image_to_ground);

// The homography of an ideal pinhole camera (no distortion) with intrinsics K and pose body ← optical frame
// (x right, y down, z forward) over the ground plane z = 0 of the body frame.
GroundHomography pinhole_ground_homography(const Eigen::Matrix3d& K, const Pose3& body_from_optical);

std::optional<Vec2> image_to_ground(const GroundHomography& h, const Vec2& pixel);
std::optional<Vec2> ground_to_image(const GroundHomography& h, const Vec2& ground);

}  // namespace fsd
