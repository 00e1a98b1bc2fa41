#include "drivers/sim/sensors/camera_model_view.hpp"

#include <array>
#include <cmath>

namespace fsd::sim {

namespace {
constexpr int kMaxClipVertices = 96;
using ClipBuffer = std::array<Vec3, kMaxClipVertices>;

// Sutherland–Hodgman against one plane; returns the new vertex count.
int clip_against(const Eigen::Vector4d& plane, const ClipBuffer& in, int n, ClipBuffer& out) {
  int m = 0;
  auto side = [&](const Vec3& p) { return plane.head<3>().dot(p) + plane[3]; };
  for (int i = 0; i < n && m < kMaxClipVertices - 1; ++i) {
    const Vec3& a = in[static_cast<std::size_t>(i)];
    const Vec3& b = in[static_cast<std::size_t>((i + 1) % n)];
    const double da = side(a), db = side(b);
    if (da >= 0) out[static_cast<std::size_t>(m++)] = a;
    if ((da >= 0) != (db >= 0)) out[static_cast<std::size_t>(m++)] = a + (b - a) * (da / (da - db));
  }
  return m;
}
}  // namespace

CameraView::CameraView(const CameraConfig& cfg, const Pose3& body_pose)
    : k_(camera_intrinsics(cfg)), width_(cfg.width), height_(cfg.height), draw_distance_(cfg.draw_distance) {
  const Pose3 map_from_camera = body_pose * camera_mount(cfg);
  R_ = map_from_camera.linear().transpose();
  t_ = -R_ * map_from_camera.translation();
  position_ = map_from_camera.translation();
  // Guard band one image size wide around the image: big enough that clipping there never shows, small enough
  // that fixed-point coordinates cannot overflow.
  const double g = std::max(width_, height_);
  clip_planes_ = {
      {0, 0, 1, -kNearPlane},
      {k_.fx, 0, k_.cx + g, 0},
      {-k_.fx, 0, width_ + g - k_.cx, 0},
      {0, k_.fy, k_.cy + g, 0},
      {0, -k_.fy, height_ + g - k_.cy, 0},
  };
  // The image frustum's sides through the optical centre, inward normals.
  side_normals_ = {
      Vec3(k_.fx, 0, k_.cx + 0.5).normalized(),
      Vec3(-k_.fx, 0, width_ - 0.5 - k_.cx).normalized(),
      Vec3(0, k_.fy, k_.cy + 0.5).normalized(),
      Vec3(0, -k_.fy, height_ - 0.5 - k_.cy).normalized(),
  };
}

cv::Point2d CameraView::project(const Vec3& p) const {
  return {k_.fx * p.x() / p.z() + k_.cx, k_.fy * p.y() / p.z() + k_.cy};
}

bool CameraView::may_see(const Vec3& centre_map, double radius) const {
  const Vec3 c = to_camera(centre_map);
  if (c.z() + radius < kNearPlane || c.norm() - radius > draw_distance_) return false;
  for (const auto& n : side_normals_)
    if (n.dot(c) < -radius) return false;
  return true;
}

void CameraView::add_polygon(std::span<const Vec3> poly, const cv::Scalar& colour, int object, DisplayList& list,
                             bool shadow) const {
  if (poly.size() < 3 || poly.size() > kMaxClipVertices / 2) return;
  ClipBuffer buf_a, buf_b;
  ClipBuffer* in = &buf_a;
  ClipBuffer* out = &buf_b;
  int n = static_cast<int>(poly.size());
  std::copy(poly.begin(), poly.end(), in->begin());
  for (const auto& plane : clip_planes_) {
    bool all_inside = true;
    for (int i = 0; i < n && all_inside; ++i)
      all_inside = plane.head<3>().dot((*in)[static_cast<std::size_t>(i)]) + plane[3] >= 0;
    if (all_inside) continue;
    n = clip_against(plane, *in, n, *out);
    if (n < 3) return;
    std::swap(in, out);
  }
  DrawPolygon d;
  d.first = static_cast<int>(list.points.size());
  d.count = n;
  d.colour = colour;
  d.object = object;
  constexpr double scale = 1 << kSubpixelBits;
  for (int i = 0; i < n; ++i) {
    const cv::Point2d p = project((*in)[static_cast<std::size_t>(i)]);
    list.points.emplace_back(static_cast<int>(std::lround(p.x * scale)), static_cast<int>(std::lround(p.y * scale)));
  }
  (shadow ? list.shadows : list.polygons).push_back(d);
}

}  // namespace fsd::sim
