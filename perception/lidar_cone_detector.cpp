#include "perception/lidar_cone_detector.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "perception/ground_split.hpp"

namespace fsd {

void describe_lidar_detector_config(ConfigSchema& schema) {
  describe_car(schema);
  roi_section().describe(schema);
  ground_section().describe(schema);
  accumulation_section().describe(schema);
  cluster_section().describe(schema);
  cone_size_section().describe(schema);
  touching_cones_section().describe(schema);
  intensity_colour_section().describe(schema);
  cone_quality_section().describe(schema);
}

LidarDetectorConfig read_lidar_detector_config(const Config& cfg) {
  LidarDetectorConfig c;
  c.roi = roi_section().read(cfg);
  c.roi.cut_out(read_car(cfg));
  c.ground = ground_section().read(cfg);
  c.accumulation = accumulation_section().read(cfg);
  c.cluster = cluster_section().read(cfg);
  c.size = cone_size_section().read(cfg);
  c.touching = touching_cones_section().read(cfg);
  c.colour = intensity_colour_section().read(cfg);
  c.quality = cone_quality_section().read(cfg);
  return c;
}

namespace {

void check_config(const LidarDetectorConfig& cfg) {
  if (cfg.ground.method != "grid_lsq" && cfg.ground.method != "pcl_sac")
    throw std::invalid_argument("perception.lidar.ground.method: unknown method '" + cfg.ground.method + "'");
  if (cfg.cluster.method != "grid" && cfg.cluster.method != "pcl_euclidean")
    throw std::invalid_argument("perception.lidar.cluster.method: unknown method '" + cfg.cluster.method + "'");
  if (cfg.ground.height_min > cfg.ground.height_max)
    throw std::invalid_argument("perception.lidar.ground: height_min above height_max");
}

}  // namespace

LidarConeDetector::LidarConeDetector(const LidarDetectorConfig& cfg, const Pose3& body_from_sensor)
    : cfg_(cfg),
      body_from_sensor_(body_from_sensor),
      roi_(cfg.roi),
      ground_(cfg.ground),
      accumulator_(cfg.accumulation),
      clusterer_(cfg.cluster),
      size_(cfg.size),
      touching_(cfg.touching, cfg.size.azimuth_step_deg, cfg.colour.reject_black ? cfg.colour.black_max : -1.0),
      shadow_(deg2rad(cfg.size.azimuth_step_deg)),
      colour_(cfg.colour, cfg.size.small_height, cfg.size.big_height) {
  check_config(cfg);
}

void LidarConeDetector::reset() {
  accumulator_.clear();
  last_ground_ = GroundPlane{};
}

LidarDetection LidarConeDetector::detect(const Scan& scan, const BodyPoseAt& pose_at) {
  LidarDetection out;
  auto& n = out.counters;
  n.input = scan.points.size();
  const auto [t0, t1] = firing_span(scan);
  out.detections.stamp = t1;

  // Deskew into the body frame at the last firing, and crop.
  const ScanMotion motion(body_from_sensor_, t0, t1, t1, pose_at, cfg_.accumulation.deskew_knots);
  cropped_.clear();
  cropped_.reserve(scan.points.size());
  // The grazing-beam test needs the lasers: a cloud from a file may have none.
  bool rings_known = false;
  for (const auto& q : scan.points)
    if (q.ring != scan.points.front().ring) {
      rings_known = true;
      break;
    }
  const bool use_grazing = cfg_.ground.grazing_band > 0 && rings_known;
  const double margin = use_grazing ? cfg_.ground.grazing_margin : 0.0;  // neighbours of the grazing test
  for (const auto& q : scan.points) {
    if (!std::isfinite(q.x) || !std::isfinite(q.y) || !std::isfinite(q.z) || !std::isfinite(q.t)) {
      ++n.invalid;
      continue;
    }
    const Eigen::Vector3f p = motion.to_reference(Eigen::Vector3f(q.x, q.y, q.z), q.t);
    if (!roi_.in_box(p.x(), p.y(), margin)) {
      ++n.outside_roi;
      continue;
    }
    if (margin > 0 && !roi_.in_box(p.x(), p.y())) ++n.outside_roi;  // a neighbour only
    if (roi_.in_body(p.x(), p.y())) {
      ++n.in_body;
      continue;
    }
    Point b = q;
    b.x = p.x(), b.y = p.y(), b.z = p.z();
    cropped_.push_back(b);
  }

  // Ground plane; the previous one (or the nominal plane) when none is found.
  GroundPlane plane = ground_.fit(cropped_);
  if (!plane.valid) {
    n.ground_fallback = true;
    if (last_ground_.inliers > 0) {
      plane = last_ground_;
    } else {
      plane = GroundPlane{};
      plane.h = std::clamp(0.0, cfg_.ground.height_min, cfg_.ground.height_max);
    }
    plane.valid = false;
  } else {
    last_ground_ = plane;
  }
  out.ground = plane;
  GroundSurface surface(plane);
  LocalGroundConfig local;
  local.cell = cfg_.ground.local_cell;
  local.band = cfg_.ground.local_band;
  local.flat = cfg_.ground.distance_threshold;
  local.min_points = cfg_.ground.local_min_points;
  local.min_extent = cfg_.ground.local_min_extent;
  local.min_fill = cfg_.ground.local_min_fill;
  local.azimuth_step = deg2rad(cfg_.size.azimuth_step_deg);
  local.sensor = body_from_sensor_.translation().head<2>();
  surface.fit_local(cropped_, local);
  n.local_ground_cells = surface.corrected_cells();
  obstacles_.clear();
  const double tau = cfg_.ground.distance_threshold;
  GrazingBeams grazing;
  grazing.sensor = body_from_sensor_.translation();
  grazing.band = cfg_.ground.grazing_band;
  grazing.drop = cfg_.ground.grazing_drop;
  grazing.window = deg2rad(cfg_.ground.grazing_window_deg);
  const auto split =
      splitter_.split(cropped_, surface, tau, cfg_.roi.max_height, &out.ground_points, obstacles_,
                      use_grazing ? &grazing : nullptr, [this](const Point& q) { return roi_.in_box(q.x, q.y); });
  n.grazing = split.grazing;
  n.ground = split.ground;
  n.below_ground = split.below;
  n.above_roi = split.above;
  n.obstacles = split.obstacles;

  // Accumulation (only with known motion), then clustering in the current body frame. The odometry's poses are
  // planar; each frame's own ground plane adds the body's pitch and roll, which would otherwise tilt an earlier
  // frame's far returns by centimetres against the current ground as the car turns or brakes.
  if (motion.has_motion()) {
    n.accumulation_dropped = accumulator_.add(obstacles_, motion.reference_pose() * plane.level_from_frame());
    accumulator_.collect(out.obstacle_points);
    out.frames = static_cast<int>(accumulator_.frames());
  } else {
    out.obstacle_points = obstacles_;
    out.frames = 1;
  }
  n.clustered = out.obstacle_points.size();
  const Vec3 sensor = body_from_sensor_.translation();
  std::size_t too_large = 0;
  const auto clusters = clusterer_.cluster(out.obstacle_points, sensor.head<2>(), &too_large);
  n.clusters = clusters.size();
  n.clusters_too_large = too_large;

  const std::vector<Vec2> tall = size_.tall_points(out.obstacle_points, surface);
  shadow_.build(out.obstacle_points, sensor.head<2>());
  const auto judge = [&](const Cluster& cl) {
    ConeMeasurement m = size_.measure(out.obstacle_points, cl, surface, body_from_sensor_, tau, out.frames, &shadow_);
    if (m.rejection == ConeRejection::None && size_.beside_taller(m.candidate.position, tall))
      m.rejection = ConeRejection::BesideTaller;
    if (m.rejection == ConeRejection::None && cfg_.colour.reject_black && colour_.black(m.candidate, surface))
      m.rejection = ConeRejection::Black;
    return m;
  };
  std::vector<ConeMeasurement> cones;
  for (const auto& cl : clusters) {
    ConeMeasurement m = judge(cl);
    if (m.rejection == ConeRejection::TooWide || m.rejection == ConeRejection::NotConeShaped) {
      // Touching cones (too wide together, or wider than a cone at some height where one stands behind the
      // other): kept when every part of the split is a cone by itself.
      std::vector<ConeMeasurement> parts;
      for (const auto& part : touching_.split(out.obstacle_points, cl, surface, sensor.head<2>())) {
        parts.push_back(judge(part));
        if (parts.back().rejection != ConeRejection::None) break;
      }
      if (parts.size() >= 2 && std::all_of(parts.begin(), parts.end(), [](const ConeMeasurement& p) {
            return p.rejection == ConeRejection::None;
          })) {
        ++n.split_clusters;
        n.split_cones += parts.size();
        for (auto& p : parts) cones.push_back(std::move(p));
        continue;
      }
    }
    if (m.rejection != ConeRejection::None) {
      const auto& c = m.candidate;
      out.rejected.push_back({c.position, c.width, c.height, c.bottom, c.points, m.rejection});
    }
    switch (m.rejection) {
      case ConeRejection::None:
        break;
      case ConeRejection::TooSparse:
        ++n.too_sparse;
        continue;
      case ConeRejection::TooWide:
        ++n.too_wide;
        continue;
      case ConeRejection::TooTall:
        ++n.too_tall;
        continue;
      case ConeRejection::NotConeShaped:
        ++n.not_cone_shaped;
        continue;
      case ConeRejection::TooFlat:
        ++n.too_flat;
        continue;
      case ConeRejection::Floating:
        ++n.floating;
        continue;
      case ConeRejection::BesideTaller:
        ++n.beside_taller;
        continue;
      case ConeRejection::Black:
        ++n.black;
        continue;
    }
    cones.push_back(std::move(m));
  }
  for (auto& m : cones) {
    const ConeCandidate& c = m.candidate;
    Cone cone;
    cone.position = c.position;
    cone.covariance = cone_covariance(cfg_.quality, c.position.head<2>(), sensor.head<2>());
    cone.confidence = cone_confidence(cfg_.quality, c.range, c.points, m.expected_points);
    cone.stage = DetectionStage::Lidar;
    cone.points = c.points;
    const IntensityColour colour = colour_.classify(c, surface);
    cone.colour = colour.colour;
    cone.colour_confidence = colour.confidence;
    cone.colour_source = colour.colour == ConeColour::Unknown ? ColourSource::None : ColourSource::LidarIntensity;
    n.coloured += colour.colour != ConeColour::Unknown;
    out.detections.cones.push_back(cone);
    out.candidates.push_back(std::move(m.candidate));
  }
  n.cones = out.detections.cones.size();
  return out;
}

}  // namespace fsd
