#include "drivers/camera/ground_homography.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <sstream>
#include <vector>

#include <opencv2/imgproc.hpp>

namespace fsd {

namespace {
// Three points count as collinear when the triangle's height over its longest side is below this share of it.
constexpr double kCollinearity = 1e-3;
constexpr double kMinW = 1e-12;

double w_of(const cv::Matx33d& H, const cv::Point2d& p) { return H(2, 0) * p.x + H(2, 1) * p.y + H(2, 2); }

std::optional<cv::Point2d> apply(const cv::Matx33d& H, const cv::Point2d& p) {
  const cv::Vec3d q = H * cv::Vec3d(p.x, p.y, 1.0);
  if (!(q[2] > kMinW * (std::abs(q[0]) + std::abs(q[1]) + 1.0))) return std::nullopt;
  return cv::Point2d(q[0] / q[2], q[1] / q[2]);
}

void check_quad(const PointQuad& q, const std::string& what) {
  for (std::size_t i = 0; i < q.size(); ++i)
    if (!std::isfinite(q[i].x) || !std::isfinite(q[i].y))
      throw HomographyError(what + ": point " + std::to_string(i + 1) + " is not a finite number");
  for (std::size_t a = 0; a < 4; ++a)
    for (std::size_t b = a + 1; b < 4; ++b)
      for (std::size_t c = b + 1; c < 4; ++c) {
        const cv::Point2d ab = q[b] - q[a], ac = q[c] - q[a], bc = q[c] - q[b];
        const double longest = std::max({cv::norm(ab), cv::norm(ac), cv::norm(bc)});
        const double height = std::abs(ab.cross(ac)) / std::max(longest, 1e-300);
        if (longest == 0.0 || height < kCollinearity * longest)
          throw HomographyError(what + ": points " + std::to_string(a + 1) + ", " + std::to_string(b + 1) + " and " +
                                std::to_string(c + 1) +
                                " are (nearly) collinear or repeated; four points with no three on a line are needed");
      }
}

bool finite(const cv::Matx33d& m) {
  for (int i = 0; i < 9; ++i)
    if (!std::isfinite(m.val[i])) return false;
  return true;
}

// Scales H so that w > 0 at `p` (a point known to be in front of the camera).
cv::Matx33d positive_at(const cv::Matx33d& H, const cv::Point2d& p) { return w_of(H, p) < 0 ? H * -1.0 : H; }

double parse_number(const std::string& s, const std::string& what) {
  std::size_t b = s.find_first_not_of(" \t"), e = s.find_last_not_of(" \t");
  const std::string t = b == std::string::npos ? "" : s.substr(b, e - b + 1);
  double v = 0;
  const auto [ptr, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
  if (t.empty() || ec != std::errc() || ptr != t.data() + t.size() || !std::isfinite(v))
    throw HomographyError(what + ": '" + t + "' is not a number");
  return v;
}
}  // namespace

GroundHomography compute_ground_homography(const PointQuad& image_points, const PointQuad& ground_points) {
  check_quad(image_points, "image points");
  check_quad(ground_points, "ground points");
  std::array<cv::Point2f, 4> src, dst;
  for (std::size_t i = 0; i < 4; ++i) {
    src[i] = cv::Point2f(static_cast<float>(image_points[i].x), static_cast<float>(image_points[i].y));
    dst[i] = cv::Point2f(static_cast<float>(ground_points[i].x), static_cast<float>(ground_points[i].y));
  }
  const cv::Matx33d m(cv::getPerspectiveTransform(src.data(), dst.data()));
  GroundHomography h = make_ground_homography(positive_at(m, image_points[0]));
  for (std::size_t i = 1; i < 4; ++i)
    if (!(w_of(h.image_to_ground, image_points[i]) > 0.0))
      throw HomographyError(
          "image and ground points do not correspond: the quadrilaterals are in a different order (list both in "
          "the same order, e.g. near left, near right, far right, far left)");
  return h;
}

GroundHomography make_ground_homography(const cv::Matx33d& image_to_ground) {
  if (!finite(image_to_ground)) throw HomographyError("homography has a non-finite entry");
  const double det = cv::determinant(image_to_ground);
  double scale = 0;
  for (int i = 0; i < 9; ++i) scale = std::max(scale, std::abs(image_to_ground.val[i]));
  if (!(scale > 0) || !(std::abs(det) > 1e-12 * scale * scale * scale))
    throw HomographyError("homography is singular (determinant " + std::to_string(det) + ")");
  GroundHomography h;
  h.image_to_ground = image_to_ground;
  h.ground_to_image = image_to_ground.inv();
  if (!finite(h.ground_to_image)) throw HomographyError("homography cannot be inverted");
  return h;
}

GroundHomography pinhole_ground_homography(const cv::Matx33d& K, const Pose3& body_from_optical) {
  const Pose3 optical_from_body = body_from_optical.inverse();
  const Eigen::Matrix3d R = optical_from_body.linear();
  const Vec3 t = optical_from_body.translation();
  // A ground point (x, y, 0) lands on K·(x·r1 + y·r2 + t).
  cv::Matx33d Rt;
  for (int r = 0; r < 3; ++r) {
    Rt(r, 0) = R(r, 0);
    Rt(r, 1) = R(r, 1);
    Rt(r, 2) = t(r);
  }
  // w is the point's depth along the optical axis: positive in front of the camera, as required.
  return make_ground_homography((K * Rt).inv());
}

std::optional<cv::Point2d> image_to_ground(const GroundHomography& h, const cv::Point2d& pixel) {
  return apply(h.image_to_ground, pixel);
}

std::optional<cv::Point2d> ground_to_image(const GroundHomography& h, const cv::Point2d& ground) {
  return apply(h.ground_to_image, ground);
}

PointQuad parse_point_quad(const std::string& text, const std::string& what) {
  std::vector<std::string> parts;
  std::stringstream ss(text);
  for (std::string item; std::getline(ss, item, ';');) parts.push_back(item);
  if (!text.empty() && text.back() == ';') parts.push_back("");
  if (parts.size() != 4)
    throw HomographyError(what + ": expected 4 points 'a,b;a,b;a,b;a,b', got " + std::to_string(parts.size()));
  PointQuad q;
  for (std::size_t i = 0; i < 4; ++i) {
    const auto comma = parts[i].find(',');
    if (comma == std::string::npos || parts[i].find(',', comma + 1) != std::string::npos)
      throw HomographyError(what + ": point " + std::to_string(i + 1) + " '" + parts[i] +
                            "' is not two numbers separated by a comma");
    const std::string label = what + " point " + std::to_string(i + 1);
    q[i] = cv::Point2d(parse_number(parts[i].substr(0, comma), label), parse_number(parts[i].substr(comma + 1), label));
  }
  return q;
}

}  // namespace fsd
