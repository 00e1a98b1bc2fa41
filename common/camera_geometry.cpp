#include "common/camera_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include <Eigen/LU>

#include "common/rotation.hpp"

namespace fsd {

namespace {
// Three points count as collinear when the triangle's height over its longest side is below this share of it.
constexpr double kCollinearity = 1e-3;
constexpr double kMinW = 1e-12;

double w_of(const Eigen::Matrix3d& H, const Vec2& p) { return H(2, 0) * p.x() + H(2, 1) * p.y() + H(2, 2); }

std::optional<Vec2> apply(const Eigen::Matrix3d& H, const Vec2& p) {
  const Vec3 q = H * p.homogeneous();
  if (!(q.z() > kMinW * (std::abs(q.x()) + std::abs(q.y()) + 1.0))) return std::nullopt;
  return Vec2(q.x() / q.z(), q.y() / q.z());
}

void check_quad(const PointQuad& q, const std::string& what) {
  for (std::size_t i = 0; i < q.size(); ++i)
    if (!q[i].allFinite()) throw HomographyError(what + ": point " + std::to_string(i + 1) + " is not a finite number");
  for (std::size_t a = 0; a < 4; ++a)
    for (std::size_t b = a + 1; b < 4; ++b)
      for (std::size_t c = b + 1; c < 4; ++c) {
        const Vec2 ab = q[b] - q[a], ac = q[c] - q[a], bc = q[c] - q[b];
        const double longest = std::max({ab.norm(), ac.norm(), bc.norm()});
        const double height = std::abs(cross2(ab, ac)) / std::max(longest, 1e-300);
        if (longest == 0.0 || height < kCollinearity * longest)
          throw HomographyError(what + ": points " + std::to_string(a + 1) + ", " + std::to_string(b + 1) + " and " +
                                std::to_string(c + 1) +
                                " are (nearly) collinear or repeated; four points with no three on a line are needed");
      }
}

// Scales H so that w > 0 at `p` (a point known to be in front of the camera).
Eigen::Matrix3d positive_at(const Eigen::Matrix3d& H, const Vec2& p) {
  return w_of(H, p) < 0 ? Eigen::Matrix3d(-H) : H;
}

// The perspective transform of four pairs with h33 = 1: eight linear equations in the other eight entries, as
// cv::getPerspectiveTransform sets them up.
Eigen::Matrix3d four_point_transform(const PointQuad& from, const PointQuad& to) {
  Eigen::Matrix<double, 8, 8> A = Eigen::Matrix<double, 8, 8>::Zero();
  Eigen::Matrix<double, 8, 1> b;
  for (int i = 0; i < 4; ++i) {
    const double u = from[static_cast<std::size_t>(i)].x(), v = from[static_cast<std::size_t>(i)].y();
    const double x = to[static_cast<std::size_t>(i)].x(), y = to[static_cast<std::size_t>(i)].y();
    A.row(2 * i) << u, v, 1, 0, 0, 0, -u * x, -v * x;
    A.row(2 * i + 1) << 0, 0, 0, u, v, 1, -u * y, -v * y;
    b(2 * i) = x;
    b(2 * i + 1) = y;
  }
  const Eigen::Matrix<double, 8, 1> h = A.fullPivLu().solve(b);
  Eigen::Matrix3d H;
  H << h(0), h(1), h(2), h(3), h(4), h(5), h(6), h(7), 1.0;
  return H;
}
}  // namespace

Pose3 CameraMount::body_from_optical() const {
  Pose3 T = pose_zyx(Vec3(x, y, z), yaw, pitch, roll);
  T.linear() = T.linear() * mount_from_optical();
  return T;
}

GroundHomography compute_ground_homography(const PointQuad& image_points, const PointQuad& ground_points) {
  check_quad(image_points, "image points");
  check_quad(ground_points, "ground points");
  GroundHomography h =
      make_ground_homography(positive_at(four_point_transform(image_points, ground_points), image_points[0]));
  for (std::size_t i = 1; i < 4; ++i)
    if (!(w_of(h.image_to_ground, image_points[i]) > 0.0))
      throw HomographyError(
          "image and ground points do not correspond: the quadrilaterals are in a different order (list both in "
          "the same order, e.g. near left, near right, far right, far left)");
  return h;
}

GroundHomography make_ground_homography(const Eigen::Matrix3d& image_to_ground) {
  if (!image_to_ground.allFinite()) throw HomographyError("homography has a non-finite entry");
  const double det = image_to_ground.determinant();
  const double scale = image_to_ground.cwiseAbs().maxCoeff();
  if (!(scale > 0) || !(std::abs(det) > 1e-12 * scale * scale * scale))
    throw HomographyError("homography is singular (determinant " + std::to_string(det) + ")");
  GroundHomography h;
  h.image_to_ground = image_to_ground;
  h.ground_to_image = image_to_ground.inverse();
  if (!h.ground_to_image.allFinite()) throw HomographyError("homography cannot be inverted");
  return h;
}

GroundHomography pinhole_ground_homography(const Eigen::Matrix3d& K, const Pose3& body_from_optical) {
  const Pose3 optical_from_body = body_from_optical.inverse();
  const Eigen::Matrix3d R = optical_from_body.linear();
  // A ground point (x, y, 0) lands on K·(x·r1 + y·r2 + t).
  Eigen::Matrix3d Rt;
  Rt.col(0) = R.col(0);
  Rt.col(1) = R.col(1);
  Rt.col(2) = optical_from_body.translation();
  // w is the point's depth along the optical axis: positive in front of the camera, as required.
  return make_ground_homography((K * Rt).inverse());
}

std::optional<Vec2> image_to_ground(const GroundHomography& h, const Vec2& pixel) {
  return apply(h.image_to_ground, pixel);
}

std::optional<Vec2> ground_to_image(const GroundHomography& h, const Vec2& ground) {
  return apply(h.ground_to_image, ground);
}

}  // namespace fsd
