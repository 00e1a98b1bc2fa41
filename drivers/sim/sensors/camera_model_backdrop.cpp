#include "drivers/sim/sensors/camera_model_backdrop.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

namespace fsd::sim {

namespace {
constexpr double kMargin = 40.0;       // m of ground textured around the track's objects
constexpr double kTexel = 0.1;         // m
constexpr double kMaxTexels = 12e6;    // texels at most; coarser texels on huge tracks
constexpr double kMaskCell = 0.2;      // m: sampling of World::ground_surface
const cv::Vec3d kAsphalt(92, 94, 96);  // B, G, R
const cv::Vec3d kGrass(48, 118, 72);
const cv::Vec3d kSkyHorizon(215, 205, 195);
const cv::Vec3d kSkyZenith(205, 150, 95);

// Smooth noise in [-1, 1] over a rows × cols raster with features `cell` texels wide.
cv::Mat smooth_noise(cv::RNG& rng, int rows, int cols, double cell) {
  cv::Mat coarse(static_cast<int>(rows / cell) + 2, static_cast<int>(cols / cell) + 2, CV_32F);
  rng.fill(coarse, cv::RNG::UNIFORM, -1.0f, 1.0f);
  cv::Mat fine;
  cv::resize(coarse, fine, cv::Size(cols, rows), 0, 0, cv::INTER_CUBIC);
  return fine;
}

// Convex polygon of the image rectangle on the side l·(u, v, 1) ≤ 0 (sign = +1) or ≥ 0 (sign = −1).
std::vector<cv::Point2d> clip_image_rect(const Eigen::Vector3d& l, double sign, int w, int h) {
  const std::array<cv::Point2d, 4> rect{cv::Point2d(-0.5, -0.5), cv::Point2d(w - 0.5, -0.5),
                                        cv::Point2d(w - 0.5, h - 0.5), cv::Point2d(-0.5, h - 0.5)};
  auto side = [&](const cv::Point2d& p) { return -sign * (l[0] * p.x + l[1] * p.y + l[2]); };
  std::vector<cv::Point2d> out;
  for (std::size_t i = 0; i < rect.size(); ++i) {
    const cv::Point2d& a = rect[i];
    const cv::Point2d& b = rect[(i + 1) % rect.size()];
    const double da = side(a), db = side(b);
    if (da >= 0) out.push_back(a);
    if ((da >= 0) != (db >= 0)) out.push_back(a + (b - a) * (da / (da - db)));
  }
  return out;
}

cv::Range rows_of(const std::vector<cv::Point2d>& poly, int h) {
  double lo = h, hi = 0;
  for (const auto& p : poly) {
    lo = std::min(lo, p.y);
    hi = std::max(hi, p.y);
  }
  return {std::clamp(static_cast<int>(std::floor(lo)), 0, h), std::clamp(static_cast<int>(std::ceil(hi)) + 1, 0, h)};
}
}  // namespace

Backdrop::Backdrop(const World& world, const CameraConfig& cfg, std::uint64_t seed) : world_(world) {
  cv::RNG rng(seed ^ 0xBAC4D50Full);
  // Texture extent: everything the track places, plus a margin.
  Eigen::AlignedBox2d box(Vec2(-1, -1), Vec2(1, 1));
  for (const auto& c : world.cones()) box.extend(c.base.head<2>());
  for (const auto& d : world.distractors()) {
    box.extend(d.position);
    if (d.type == DistractorType::Fence) box.extend(d.fence_end());
  }
  box.min() -= Vec2::Constant(kMargin);
  box.max() += Vec2::Constant(kMargin);
  res_ = std::max(kTexel, std::sqrt(box.volume() / kMaxTexels));
  x0_ = box.min().x();
  y0_ = box.min().y();
  const int cols = static_cast<int>(std::ceil(box.sizes().x() / res_)) + 1;
  const int rows = static_cast<int>(std::ceil(box.sizes().y() / res_)) + 1;

  // Asphalt weight: 1 on the track surface, 0 on grass, soft at the edge.
  const int mc = static_cast<int>(std::ceil(box.sizes().x() / kMaskCell)) + 1;
  const int mr = static_cast<int>(std::ceil(box.sizes().y() / kMaskCell)) + 1;
  cv::Mat mask(mr, mc, CV_32F);
  for (int i = 0; i < mr; ++i) {
    auto* row = mask.ptr<float>(i);
    for (int j = 0; j < mc; ++j)
      row[j] = world.ground_surface(x0_ + j * kMaskCell, y0_ + i * kMaskCell) == Surface::Grass ? 0.0f : 1.0f;
  }
  cv::Mat asphalt_weight;
  cv::resize(mask, asphalt_weight, cv::Size(cols, rows), 0, 0, cv::INTER_LINEAR);

  // Brightness patterns: patches of metres, decimetre mottling, texel grain; scaled by the world's texture setting.
  const double amp = std::clamp(world.config().ground_texture / 4.0, 0.0, 3.0);
  const cv::Mat big = smooth_noise(rng, rows, cols, 3.0 / res_);
  const cv::Mat mid = smooth_noise(rng, rows, cols, 0.5 / res_);
  cv::Mat grain(rows, cols, CV_32F);
  rng.fill(grain, cv::RNG::NORMAL, 0.0f, 1.0f);
  const cv::Mat asphalt_light = 1.0 + amp * (0.08 * big + 0.05 * mid + 0.05 * grain);
  const cv::Mat grass_light = 1.0 + amp * (0.15 * big + 0.10 * mid + 0.12 * grain);
  std::array<cv::Mat, 3> channels;
  for (int c = 0; c < 3; ++c) {
    cv::Mat mixed =
        asphalt_weight.mul(asphalt_light) * kAsphalt[c] + (1.0 - asphalt_weight).mul(grass_light) * kGrass[c];
    mixed.convertTo(channels[static_cast<std::size_t>(c)], CV_8U);
  }
  cv::merge(channels.data(), channels.size(), texture_);
  const bool grass_beyond = world.ground_surface(box.max().x() + 1e4, box.max().y() + 1e4) == Surface::Grass;
  const cv::Vec3d beyond = grass_beyond ? kGrass : kAsphalt;
  beyond_ = cv::Scalar(beyond[0], beyond[1], beyond[2]);

  // Sky: pale at the level horizon, blue higher up, with faint clouds.
  const PinholeIntrinsics k = camera_intrinsics(cfg);
  const double horizon_v = k.cy - k.fy * std::tan(cfg.pitch);
  const cv::Mat clouds = smooth_noise(rng, cfg.height, cfg.width, cfg.width / 6.0);
  sky_.create(cfg.height, cfg.width, CV_8UC3);
  for (int v = 0; v < cfg.height; ++v) {
    const double s = std::clamp((horizon_v - v) / (0.6 * cfg.height), 0.0, 1.0);
    const cv::Vec3d base = kSkyHorizon * (1.0 - s) + kSkyZenith * s;
    auto* row = sky_.ptr<cv::Vec3b>(v);
    const auto* cloud = clouds.ptr<float>(v);
    for (int u = 0; u < cfg.width; ++u) {
      const double white = std::clamp(cloud[u] - 0.2, 0.0, 1.0) * 0.8 * s;
      const cv::Vec3d c = base * (1.0 - white) + cv::Vec3d(235, 235, 235) * white;
      row[u] =
          cv::Vec3b(cv::saturate_cast<uchar>(c[0]), cv::saturate_cast<uchar>(c[1]), cv::saturate_cast<uchar>(c[2]));
    }
  }
}

void Backdrop::paint(const CameraView& view, const cv::Scalar& gains, cv::Mat& frame) const {
  const int w = view.width(), h = view.height();
  frame.create(h, w, CV_8UC3);
  const PinholeIntrinsics& k = view.intrinsics();
  Eigen::Matrix3d K;
  K << k.fx, 0, k.cx, 0, k.fy, k.cy, 0, 0, 1;
  // The ground's vanishing line l = K^-T·n: a pixel p sees the ground ahead when l·p < 0.
  const Vec3 n_cam = view.rotation() * world_.ground_normal();
  const Eigen::Vector3d l = K.inverse().transpose() * n_cam;
  const auto ground_poly = clip_image_rect(l, +1.0, w, h);
  const auto sky_poly = clip_image_rect(l, -1.0, w, h);

  if (ground_poly.size() >= 3) {
    // Texel (j, i, 1) → map point on the plane z = sx·x + sy·y → camera → pixel, shifted to the painted rows.
    const cv::Range rows = rows_of(ground_poly, h);
    const Vec3 n = world_.ground_normal();
    const double sx = -n.x() / n.z(), sy = -n.y() / n.z();
    Eigen::Matrix3d M;
    M.col(0) = view.rotation() * Vec3(res_, 0, sx * res_);
    M.col(1) = view.rotation() * Vec3(0, res_, sy * res_);
    M.col(2) = view.to_camera(Vec3(x0_, y0_, sx * x0_ + sy * y0_));
    // Warped at half resolution and enlarged: the texture is coarser than a pixel near the car anyway, and this
    // halves the cost of the biggest step of a frame. Half-size pixel (u', v') is full-size (2u' + 0.5, 2v' + 0.5).
    Eigen::Matrix3d to_half;
    to_half << 0.5, 0, -0.25, 0, 0.5, -0.25 - 0.5 * rows.start, 0, 0, 1;
    const Eigen::Matrix3d H = to_half * K * M;
    cv::Matx33d Hcv;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) Hcv(r, c) = H(r, c);
    cv::Mat target = frame.rowRange(rows);
    cv::Mat half;
    cv::warpPerspective(texture_, half, Hcv, cv::Size((w + 1) / 2, (rows.size() + 1) / 2), cv::INTER_LINEAR,
                        cv::BORDER_CONSTANT, beyond_);
    cv::resize(half, target, target.size(), 0, 0, cv::INTER_LINEAR);
  }
  if (sky_poly.size() >= 3) {
    const cv::Range rows = rows_of(sky_poly, h);
    if (ground_poly.size() < 3) {
      sky_.rowRange(rows).copyTo(frame.rowRange(rows));
    } else {
      cv::Mat mask(rows.size(), w, CV_8U, cv::Scalar(0));
      std::vector<cv::Point> pts;
      constexpr double scale = 1 << kSubpixelBits;
      for (const auto& p : sky_poly)
        pts.emplace_back(static_cast<int>(std::lround((p.x) * scale)),
                         static_cast<int>(std::lround((p.y - rows.start) * scale)));
      cv::fillConvexPoly(mask, pts, cv::Scalar(255), cv::LINE_8, kSubpixelBits);
      sky_.rowRange(rows).copyTo(frame.rowRange(rows), mask);
    }
  }
  cv::multiply(frame, gains, frame);
}

}  // namespace fsd::sim
