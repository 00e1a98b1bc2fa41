#include "drivers/sim/sensors/camera_model.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "drivers/sim/world/world_random.hpp"

namespace fsd::sim {

namespace {
constexpr int kNoiseMargin = 64;  // px: the noise bank is this much larger than a frame, read at a random offset
constexpr std::uint64_t kNoiseStream = 0x9015Eu;
constexpr double kFixedPoint = 1 << kSubpixelBits;

void fill(cv::Mat& img, const DisplayList& list, const DrawPolygon& p, const cv::Scalar& colour,
          cv::Point offset = {0, 0}) {
  if (offset == cv::Point(0, 0)) {
    cv::fillConvexPoly(img, &list.points[static_cast<std::size_t>(p.first)], p.count, colour, cv::LINE_8,
                       kSubpixelBits);
    return;
  }
  std::vector<cv::Point> pts(list.points.begin() + p.first, list.points.begin() + p.first + p.count);
  for (auto& q : pts) q -= offset * (1 << kSubpixelBits);
  cv::fillConvexPoly(img, pts, colour, cv::LINE_8, kSubpixelBits);
}
}  // namespace

CameraModel::CameraModel(const CameraConfig& cfg, const World& world, std::uint64_t seed, Stamp start)
    : cfg_(cfg),
      world_(world),
      seed_(seed),
      start_(start),
      sun_(cfg),
      backdrop_(world, cfg, seed),
      scene_(world, sun_) {
  if (cfg_.pixel_noise > 0.0) {
    cv::RNG rng(hash64(seed, kNoiseStream));
    cv::Mat noise(cfg.height + kNoiseMargin, cfg.width + kNoiseMargin, CV_16SC3);
    rng.fill(noise, cv::RNG::NORMAL, 0.0, cfg_.pixel_noise);
    cv::Mat positive = cv::max(noise, 0), negative = cv::max(-noise, 0);
    positive.convertTo(noise_up_, CV_8U);
    negative.convertTo(noise_down_, CV_8U);
  }
}

void CameraModel::advance_to(Stamp t, const std::function<Pose3(Stamp)>& body_pose_at, const ByteSink& sink) {
  while (next_capture() <= t) {
    const Stamp capture = next_capture();
    render_into(body_pose_at(capture), capture, frames_, frame_);
    cv::imencode(".jpg", frame_, jpeg_, {cv::IMWRITE_JPEG_QUALITY, cfg_.jpeg_quality});
    ++frames_;
    if (sink) sink(capture + cfg_.latency, jpeg_);
  }
}

cv::Mat CameraModel::render(const Pose3& body_pose, Stamp t) const {
  cv::Mat out;
  render_into(body_pose, t, std::bit_cast<std::uint64_t>(t), out);
  return out;
}

void CameraModel::render_into(const Pose3& body_pose, Stamp t, std::uint64_t noise_key, cv::Mat& out) const {
  const CameraView view(cfg_, body_pose);
  const cv::Scalar gains = exposure_at(cfg_, seed_, t).channel_gains();
  backdrop_.paint(view, gains, out);
  DisplayList list;
  scene_.build(view, gains, true, list);

  // Shadows: the ground inside them keeps only the ambient part of its light.
  if (!list.shadows.empty()) {
    cv::Mat mask(out.size(), CV_8U, cv::Scalar(0));
    for (const auto& s : list.shadows) fill(mask, list, s, cv::Scalar(255));
    const cv::Rect roi = cv::boundingRect(mask);
    if (roi.area() > 0) {
      const double shadow = sun_.shade(Vec3::Zero()) / sun_.shade(world_.ground_normal());
      cv::Mat dark;
      out(roi).convertTo(dark, -1, shadow);
      dark.copyTo(out(roi), mask(roi));
    }
  }
  for (const auto& p : list.polygons) fill(out, list, p, p.colour);
  if (cfg_.blur > 0.0) {
    // Kernel out to 1.5 σ (3×3 for the default): the tails beyond add nothing visible at this blur.
    const int half = static_cast<int>(std::ceil(1.5 * cfg_.blur));
    cv::GaussianBlur(out, out, cv::Size(2 * half + 1, 2 * half + 1), cfg_.blur);
  }
  add_noise(noise_key, out);
}

void CameraModel::add_noise(std::uint64_t noise_key, cv::Mat& img) const {
  if (noise_up_.empty()) return;
  const std::uint64_t h = hash64(seed_, kNoiseStream, noise_key);
  const cv::Rect window(static_cast<int>(h % kNoiseMargin), static_cast<int>((h >> 16) % kNoiseMargin), img.cols,
                        img.rows);
  cv::add(img, noise_up_(window), img);
  cv::subtract(img, noise_down_(window), img);
}

std::vector<ProjectedCone> CameraModel::visible_cones(const Pose3& body_pose) const {
  const CameraView view(cfg_, body_pose);
  DisplayList list;
  scene_.build(view, cv::Scalar::all(1), false, list);
  cv::Mat ids(cfg_.height, cfg_.width, CV_16U, cv::Scalar(0));
  for (const auto& p : list.polygons) fill(ids, list, p, cv::Scalar(p.object + 1));

  const int cones = static_cast<int>(world_.cones().size());
  std::vector<std::vector<const DrawPolygon*>> by_cone(static_cast<std::size_t>(cones));
  for (const auto& p : list.polygons)
    if (p.object < cones) by_cone[static_cast<std::size_t>(p.object)].push_back(&p);

  const cv::Rect image(0, 0, cfg_.width, cfg_.height);
  std::vector<ProjectedCone> out;
  for (int i = 0; i < cones; ++i) {
    const auto& polys = by_cone[static_cast<std::size_t>(i)];
    if (polys.empty()) continue;
    double x0 = std::numeric_limits<double>::max(), y0 = x0, x1 = -x0, y1 = -x0;
    for (const auto* p : polys)
      for (int k = 0; k < p->count; ++k) {
        const cv::Point& q = list.points[static_cast<std::size_t>(p->first + k)];
        x0 = std::min(x0, q.x / kFixedPoint);
        x1 = std::max(x1, q.x / kFixedPoint);
        y0 = std::min(y0, q.y / kFixedPoint);
        y1 = std::max(y1, q.y / kFixedPoint);
      }
    const cv::Rect around =
        cv::Rect(cv::Point(static_cast<int>(std::floor(x0)) - 1, static_cast<int>(std::floor(y0)) - 1),
                 cv::Point(static_cast<int>(std::ceil(x1)) + 2, static_cast<int>(std::ceil(y1)) + 2)) &
        image;
    if (around.area() == 0) continue;
    // The silhouette alone, then how much of it the painted image still shows.
    cv::Mat alone(around.size(), CV_8U, cv::Scalar(0));
    for (const auto* p : polys) fill(alone, list, *p, cv::Scalar(255), around.tl());
    const int area = cv::countNonZero(alone);
    if (area == 0) continue;
    const cv::Mat shown = (ids(around) == i + 1) & alone;
    const WorldCone& c = world_.cones()[static_cast<std::size_t>(i)];
    ProjectedCone pc;
    pc.index = i;
    pc.colour = c.colour;
    pc.big = c.big;
    pc.knocked = c.knocked;
    pc.box = cv::boundingRect(alone) + around.tl();
    pc.truncated = x0 < -0.5 || y0 < -0.5 || x1 > cfg_.width - 0.5 || y1 > cfg_.height - 0.5;
    pc.visible_fraction = static_cast<double>(cv::countNonZero(shown)) / area;
    const Vec3 base = view.to_camera(c.base);
    pc.distance = base.norm();
    pc.base_pixel = base.z() > 0 ? view.project(base) : cv::Point2d(std::nan(""), std::nan(""));
    out.push_back(pc);
  }
  std::sort(out.begin(), out.end(),
            [](const ProjectedCone& a, const ProjectedCone& b) { return a.distance > b.distance; });
  return out;
}

}  // namespace fsd::sim
