#pragma once
// The camera's calibration file (JSON): intrinsics, mounting on the vehicle, and the ground homography of the
// paper's perspective-transform calibration. Each section is optional, so `fsd calibrate-homography` can write a
// file with the homography alone and add it to an existing one. docs/camera.md shows the format.
//
//   { "format": "fsd-camera-calibration", "version": 1,
//     "intrinsics": { "width": 640, "height": 480, "K": [[fx,0,cx],[0,fy,cy],[0,0,1]], "distortion": [k1,k2,p1,p2,k3] },
//     "extrinsics": { "x": 0.5, "y": 0, "z": 1.05, "roll": 0, "pitch": 0.1, "yaw": 0 },
//     "homography": { "image_to_ground": [[..],[..],[..]],
//                     "image_points": [[u,v] ×4], "ground_points": [[x,y] ×4] } }
//
// Extrinsics place the camera body frame (x forward, y left, z up; pitch positive looks down; Z-Y-X angles, rad) on
// the vehicle body frame (rear-axle centre on the ground, metres), like the LiDAR mount in the configuration.
#include <array>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>
#include <opencv2/core/matx.hpp>

#include "common/geometry.hpp"
#include "drivers/camera/ground_homography.hpp"

namespace fsd {

// Thrown for unreadable, unwritable or invalid calibration files; what() names the file and the field.
class CalibrationError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct CameraIntrinsics {
  int width = 0, height = 0;        // image size the calibration belongs to
  cv::Matx33d K = cv::Matx33d::eye();
  std::vector<double> distortion;   // OpenCV order (k1, k2, p1, p2[, k3[, k4, k5, k6[, s1..s4[, τx, τy]]]]), or empty
};

struct CameraMount {
  double x = 0, y = 0, z = 0;
  double roll = 0, pitch = 0, yaw = 0;
  // Body ← optical frame (x right, y down, z forward).
  Pose3 body_from_optical() const;
};

struct HomographyCalibration {
  GroundHomography homography;
  std::optional<PointQuad> image_points, ground_points;  // the pairs it was computed from, if known
};

struct CameraCalibration {
  std::optional<CameraIntrinsics> intrinsics;
  std::optional<CameraMount> extrinsics;
  std::optional<HomographyCalibration> homography;
};

// `origin` names the source (file) in error messages.
CameraCalibration parse_camera_calibration(const nlohmann::json& j, const std::string& origin);
nlohmann::json to_json(const CameraCalibration& c);

CameraCalibration load_camera_calibration(const std::filesystem::path& file);
// Writes the file whole or not at all (temporary file, then rename).
void save_camera_calibration(const CameraCalibration& c, const std::filesystem::path& file);

}  // namespace fsd
