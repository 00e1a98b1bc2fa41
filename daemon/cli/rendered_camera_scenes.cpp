#include "daemon/cli/rendered_camera_scenes.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <numbers>

#include <opencv2/imgcodecs.hpp>

#include "common/track.hpp"
#include "drivers/sim/sensors/camera_model.hpp"
#include "drivers/sim/world/world.hpp"
#include "drivers/sim/world/world_random.hpp"

namespace fsd {

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kFencePointSpacing = 1.5;  // m between fence candidates
constexpr double kGroundClearance = 1.2;    // m from any object for a bare-ground candidate
constexpr double kLidarRoiTop = 1.0;        // m: the LiDAR ROI box ends this far above the ground (DESIGN.md §5b)

double gaussian(sim::Rng& rng) {
  const double u1 = 1.0 - rng.uniform(), u2 = rng.uniform();
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * kPi * u2);
}

// Poses along the centre line: between each left cone and the nearest right one, heading to the next such point.
std::vector<Pose2> centre_line(const Track& track) {
  std::vector<Vec2> mid;
  for (const auto& left : track.cones) {
    if (left.role != ConeRole::Left) continue;
    double best = std::numeric_limits<double>::max();
    Vec2 partner = left.position;
    for (const auto& right : track.cones)
      if (right.role == ConeRole::Right && (right.position - left.position).norm() < best) {
        best = (right.position - left.position).norm();
        partner = right.position;
      }
    mid.push_back((left.position + partner) / 2);
  }
  std::vector<Pose2> poses;
  for (std::size_t i = 0; i + 1 < mid.size(); ++i) {
    const Vec2 d = mid[i + 1] - mid[i];
    if (d.norm() > 1e-3) poses.push_back({mid[i].x(), mid[i].y(), std::atan2(d.y(), d.x())});
  }
  if (poses.empty()) poses.push_back(track.start);
  return poses;
}

sim::CameraConfig camera_for(sim::Rng& rng, bool vary) {
  sim::CameraConfig c;
  if (!vary) return c;
  c.hfov = rng.uniform(1.0, 1.5);
  c.x = rng.uniform(0.0, 1.0);
  c.z = rng.uniform(0.85, 1.3);
  c.pitch = rng.uniform(0.04, 0.18);
  c.gain = rng.uniform(0.75, 1.25);
  c.white_balance = rng.uniform(-0.08, 0.08);
  c.sun_azimuth = rng.uniform(0.0, 2 * kPi);
  c.sun_elevation = rng.uniform(0.35, 1.2);
  c.pixel_noise = rng.uniform(1.0, 3.0);
  c.blur = rng.uniform(0.4, 1.0);
  c.jpeg_quality = rng.uniform_int(70, 95);
  return c;
}

sim::WorldConfig world_config() {
  sim::WorldConfig w;  // distractors, grass and ground texture on
  w.tyres = 12;
  w.posts = 8;
  w.tyre_stacks = 6;
  w.fence_segments = 4;
  return w;
}

cv::Mat through_jpeg(const cv::Mat& img, int quality) {
  std::vector<std::uint8_t> bytes;
  cv::imencode(".jpg", img, bytes, {cv::IMWRITE_JPEG_QUALITY, quality});
  return cv::imdecode(bytes, cv::IMREAD_COLOR);
}

class SceneMaker {
 public:
  SceneMaker(const RenderedScenesConfig& cfg, const Track& track, const sim::World& world, std::uint64_t seed)
      : cfg_(cfg),
        rng_(seed),
        camera_cfg_(camera_for(rng_, cfg.vary_camera)),
        world_(world),
        camera_(camera_cfg_, world_, rng_.next()),
        calibration_(sim::calibration_of(camera_cfg_)),
        projector_(calibration_),
        poses_(centre_line(track)) {}

  RenderedFrame frame(int index) {
    RenderedFrame f;
    f.frame = index;
    f.calibration = calibration_;
    const Pose2& on_line = poses_[static_cast<std::size_t>(rng_.uniform_int(0, static_cast<int>(poses_.size()) - 1))];
    const double offset = rng_.uniform(-0.8, 0.8), yaw = on_line.yaw + rng_.uniform(-0.3, 0.3);
    const Vec2 p = on_line.position() + offset * Vec2(-std::sin(on_line.yaw), std::cos(on_line.yaw));
    const Pose3 body = Pose2{p.x(), p.y(), yaw}.to_pose3(world_.ground_height(p.x(), p.y()));
    const double t = rng_.uniform(0.0, 600.0);
    f.bgr = through_jpeg(camera_.render(body, t), camera_cfg_.jpeg_quality);
    vehicle_from_map_ = body.inverse();
    camera_ground_ = Vec2(camera_cfg_.x, camera_cfg_.y);
    visible_ = camera_.visible_cones(body);
    add_cones(f);
    add_distractors(f, body);
    add_ground(f, body);
    for (auto& c : f.candidates)
      if (!c.is_cone) c.crowded = crowded(c, f.bgr.size());
    return f;
  }

 private:
  Vec3 to_vehicle(const Vec2& map) const {
    return vehicle_from_map_ * Vec3(map.x(), map.y(), world_.ground_height(map.x(), map.y()));
  }

  RenderedCandidate candidate(const Vec3& vehicle, std::string kind) {
    RenderedCandidate c;
    c.cone.position = Vec3(vehicle.x() + cfg_.position_noise * gaussian(rng_),
                           vehicle.y() + cfg_.position_noise * gaussian(rng_), 0.0);
    c.cone.stage = DetectionStage::Lidar;
    c.cone.colour = ConeColour::Unknown;
    c.cone.colour_source = ColourSource::None;
    c.cone.colour_confidence = 0.0;
    c.kind = std::move(kind);
    c.range = (vehicle.head<2>() - camera_ground_).norm();
    return c;
  }

  bool in_view(const Vec3& vehicle) const {
    const double range = (vehicle.head<2>() - camera_ground_).norm();
    return range <= cfg_.max_range && vehicle.x() > camera_ground_.x() + 0.5;
  }

  void add_cones(RenderedFrame& f) {
    for (const auto& pc : visible_) {
      const sim::WorldCone& wc = world_.cones()[static_cast<std::size_t>(pc.index)];
      if (wc.knocked || pc.distance > cfg_.max_range) continue;
      // The LiDAR sees the near half of the cone: its centroid lies up to half a base radius towards the sensor.
      const Vec3 base = to_vehicle(wc.base.head<2>());
      const Vec2 towards = (camera_ground_ - base.head<2>()).normalized();
      const double bias = rng_.uniform(0.0, 0.5 * wc.base_width / 2);
      RenderedCandidate c = candidate(base + bias * Vec3(towards.x(), towards.y(), 0.0), "cone");
      c.is_cone = true;
      c.colour = pc.colour;
      c.visible_fraction = pc.visible_fraction;
      c.truncated = pc.truncated;
      c.truth_box = pc.box;
      c.truth_base = pc.base_pixel;
      c.size = {wc.height * rng_.uniform(0.85, 1.0), wc.base_width};  // the top ring rarely hits the tip
      f.candidates.push_back(std::move(c));
    }
  }

  void add_distractors(RenderedFrame& f, const Pose3& body) {
    const Vec2 camera_map = (body * Vec3(camera_cfg_.x, camera_cfg_.y, 0)).head<2>();
    for (const auto& d : world_.distractors()) {
      std::vector<Vec2> points;
      if (d.type == sim::DistractorType::Fence) {
        for (double s = kFencePointSpacing / 2; s < d.length; s += kFencePointSpacing)
          points.push_back(d.position + s * Vec2(std::cos(d.yaw), std::sin(d.yaw)));
      } else {
        // The LiDAR sees the near side: its cluster's centroid lies towards the sensor.
        const Vec2 towards = (camera_map - d.position).normalized();
        points.push_back(d.position + 0.5 * d.footprint_radius() * towards);
      }
      for (const Vec2& p : points) {
        const Vec3 v = to_vehicle(p);
        if (!in_view(v)) continue;
        RenderedCandidate c = candidate(v, sim::to_string(d.type));
        const double width = d.type == sim::DistractorType::Fence ? 0.3 : 2 * d.footprint_radius();
        c.size = {std::min(d.height, kLidarRoiTop), width};
        f.candidates.push_back(std::move(c));
      }
    }
  }

  bool near_an_object(const Vec2& p) const {
    for (const auto& c : world_.cones())
      if ((c.base.head<2>() - p).norm() < kGroundClearance) return true;
    for (const auto& d : world_.distractors()) {
      const double gap = d.type == sim::DistractorType::Fence
                             ? (closest_on_segment(p, d.position, d.fence_end()) - p).norm()
                             : (d.position - p).norm() - d.footprint_radius();
      if (gap < kGroundClearance) return true;
    }
    return false;
  }

  static Vec2 closest_on_segment(const Vec2& p, const Vec2& a, const Vec2& b) {
    const Vec2 ab = b - a;
    const double t = std::clamp((p - a).dot(ab) / std::max(ab.squaredNorm(), 1e-12), 0.0, 1.0);
    return a + t * ab;
  }

  void add_ground(RenderedFrame& f, const Pose3& body) {
    const double half_fov = camera_cfg_.hfov / 2 * 0.9;
    for (int k = 0, tries = 0; k < cfg_.ground_candidates && tries < 20 * cfg_.ground_candidates; ++tries) {
      const double x = rng_.uniform(3.0, cfg_.max_range), y = rng_.uniform(-1.0, 1.0) * x * std::tan(half_fov);
      const Vec2 map = (body * Vec3(camera_cfg_.x + x, camera_cfg_.y + y, 0)).head<2>();
      if (near_an_object(map)) continue;
      const bool grass = world_.ground_surface(map.x(), map.y()) == sim::Surface::Grass;
      RenderedCandidate c = candidate(to_vehicle(map), grass ? "grass" : "asphalt");
      c.size = {rng_.uniform(0.05, 0.2), rng_.uniform(0.1, 0.3)};  // a bump of ground noise
      f.candidates.push_back(std::move(c));
      ++k;
    }
  }

  // A non-cone whose ROI a visible cone covers for a quarter or more: the crop shows a cone, no clean negative.
  bool crowded(const RenderedCandidate& c, cv::Size image) const {
    const CandidateRoi roi = projector_.project(c.cone.position, image);
    const double area = std::max(1.0, roi.box.area());
    for (const auto& pc : visible_)
      if (pc.visible_fraction > 0.2 && (cv::Rect2d(pc.box) & roi.box).area() > 0.25 * area) return true;
    return false;
  }

  const RenderedScenesConfig& cfg_;
  sim::Rng rng_;
  sim::CameraConfig camera_cfg_;
  const sim::World& world_;
  sim::CameraModel camera_;
  CameraCalibration calibration_;
  ConeProjector projector_;
  std::vector<Pose2> poses_;
  Pose3 vehicle_from_map_ = Pose3::Identity();
  Vec2 camera_ground_ = Vec2::Zero();
  std::vector<sim::ProjectedCone> visible_;
};

}  // namespace

void render_camera_scenes(const RenderedScenesConfig& cfg, const std::function<void(const RenderedFrame&)>& frame_fn) {
  for (std::size_t i = 0; i < cfg.tracks.size(); ++i) {
    const bool fsac = cfg.fsac_share && i % 2 == 1;
    const Track track = load_track(cfg.tracks[i], ColourConvention::named(fsac ? "fsac" : "fsg"));
    const sim::World world(track, world_config(), sim::hash64(cfg.seed, i));
    const int per_camera = std::max(1, cfg.frames_per_camera);
    for (int first = 0; first < cfg.frames_per_track; first += per_camera) {
      SceneMaker maker(cfg, track, world, sim::hash64(cfg.seed, i, static_cast<std::uint64_t>(first) + 1));
      for (int k = first; k < std::min(cfg.frames_per_track, first + per_camera); ++k) {
        RenderedFrame f = maker.frame(k);
        f.track = std::filesystem::path(cfg.tracks[i]).stem().string();
        frame_fn(f);
      }
    }
  }
}

}  // namespace fsd
