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
// The structs (CameraCalibration, CameraIntrinsics, CameraMount, HomographyCalibration) are pure geometry in
// common/camera_geometry.hpp, so perception uses them without the file I/O.
#include <filesystem>
#include <stdexcept>
#include <string>

#include <nlohmann/json_fwd.hpp>

#include "common/camera_geometry.hpp"

namespace fsd {

// Thrown for unreadable, unwritable or invalid calibration files; what() names the file and the field.
class CalibrationError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// `origin` names the source (file) in error messages.
CameraCalibration parse_camera_calibration(const nlohmann::json& j, const std::string& origin);
nlohmann::json to_json(const CameraCalibration& c);

CameraCalibration load_camera_calibration(const std::filesystem::path& file);
// Writes the file whole or not at all (temporary file, then rename).
void save_camera_calibration(const CameraCalibration& c, const std::filesystem::path& file);

}  // namespace fsd
