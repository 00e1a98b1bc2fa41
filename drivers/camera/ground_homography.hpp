#pragma once
// Point lists of the paper's joint calibration of camera and LiDAR (§III.B.1) as `fsd calibrate-homography` takes
// them on its command line. The homography itself (GroundHomography, compute_ground_homography, image_to_ground,
// ground_to_image) is pure geometry and lives in common/camera_geometry.hpp.
#include <string>

#include "common/camera_geometry.hpp"

namespace fsd {

// Parses exactly four points written "a1,b1;a2,b2;a3,b3;a4,b4" (spaces allowed). Throws HomographyError naming
// `what` and the bad part.
PointQuad parse_point_quad(const std::string& text, const std::string& what);

}  // namespace fsd
