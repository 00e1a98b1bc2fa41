#pragma once
// Where the virtual camera is and how 3D polygons reach its image: the pose of the optical frame in the map,
// culling, clipping against the near plane and a guard band around the image, and projection to fixed-point
// pixel coordinates for OpenCV's polygon filling (pixel centres at integer coordinates).
#include <span>
#include <vector>

#include <opencv2/core/types.hpp>

#include "common/geometry.hpp"
#include "drivers/sim/sensors/camera_model_config.hpp"

namespace fsd::sim {

inline constexpr int kSubpixelBits = 4;     // fractional bits of the polygon vertices
inline constexpr double kNearPlane = 0.05;  // m

// A filled polygon: points[first, first + count) of its DisplayList, in fixed point.
struct DrawPolygon {
  int first = 0;
  int count = 0;
  cv::Scalar colour;
  int object = -1;  // cone index, or cone count + distractor index
};

// Polygons in painting order (far to near) and the shadows they cast on the ground.
struct DisplayList {
  std::vector<cv::Point> points;
  std::vector<DrawPolygon> polygons;
  std::vector<DrawPolygon> shadows;
  void clear() {
    points.clear();
    polygons.clear();
    shadows.clear();
  }
};

class CameraView {
 public:
  CameraView(const CameraConfig& cfg, const Pose3& body_pose);

  const PinholeIntrinsics& intrinsics() const { return k_; }
  int width() const { return width_; }
  int height() const { return height_; }
  const Vec3& position() const { return position_; }      // optical centre, map frame
  const Eigen::Matrix3d& rotation() const { return R_; }  // optical ← map
  Vec3 to_camera(const Vec3& p_map) const { return R_ * p_map + t_; }
  cv::Point2d project(const Vec3& p_cam) const;  // p_cam.z() > 0

  // Whether a sphere (map frame) may show in the image within the draw distance.
  bool may_see(const Vec3& centre_map, double radius) const;

  // Clips a convex polygon (camera frame) and appends it to `list` (as a polygon or a shadow) if anything remains.
  void add_polygon(std::span<const Vec3> poly_cam, const cv::Scalar& colour, int object, DisplayList& list,
                   bool shadow = false) const;

 private:
  PinholeIntrinsics k_;
  int width_, height_;
  double draw_distance_;
  Eigen::Matrix3d R_;
  Vec3 t_;
  Vec3 position_;
  std::vector<Eigen::Vector4d> clip_planes_;  // a·X + b·Y + c·Z + d ≥ 0 inside
  std::vector<Vec3> side_normals_;            // unit inward normals of the image frustum's sides
};

}  // namespace fsd::sim
