#include "localization/lidar_odometry/lidar_odometry.hpp"

#include <cmath>

namespace fsd::lidar_odometry {

namespace {

Vec6 twist_of(const Pose3& D, double dt) {
  Vec6 v;
  const Eigen::AngleAxisd aa(D.linear());
  v << D.translation() / dt, aa.axis() * aa.angle() / dt;
  return v;
}
}  // namespace

LidarOdometry::LidarOdometry(const LidarOdometryConfig& cfg, const Pose3& body_from_sensor)
    : cfg_(cfg), body_from_sensor_(body_from_sensor), extractor_(cfg.features), registration_(cfg.odometry) {}

std::vector<Vec3> LidarOdometry::deskew(const std::vector<FeaturePoint>& pts, Stamp t_ref) const {
  // Each point moved to the body frame at t_ref: body(t_ref) ← body(t) ← sensor.
  std::vector<Vec3> out;
  out.reserve(pts.size());
  for (const auto& f : pts) out.push_back(motion(velocity_, f.t - t_ref) * (body_from_sensor_ * f.p));
  return out;
}

OdometryOutput LidarOdometry::process(const Scan& scan, const std::optional<Vec6>& measured_twist) {
  OdometryOutput out;
  const bool measured = measured_twist && measured_twist->allFinite();
  if (measured) velocity_ = *measured_twist;
  const FiringSpan span = firing_span(scan);
  const Stamp t = span.last;
  const Features f = extractor_.extract(scan);
  out.diagnostics.edges = int(f.edges.size());
  out.diagnostics.planes = int(f.planes.size());
  if (!started_) {
    started_ = true;
    pose_ = origin_;
    stamp_ = t;
    const auto e = deskew(f.edges, t), p = deskew(f.planes, t);
    add_to_map(e, p, true);
    out.pose = pose_;
    out.stamp = t;
    return out;
  }
  const double dt = t - stamp_;
  if (dt <= 0) {  // out of order or a repeated scan: nothing to learn from it
    out.pose = pose_;
    out.stamp = stamp_;
    return out;
  }
  const Vec6 velocity0 = velocity_;
  auto edges = deskew(f.edges, t), planes = deskew(f.planes, t);
  const Pose3 predicted = pose_ * motion(velocity_, dt);
  Alignment a = registration_.align(edges, planes, map_, predicted);
  Pose3 delta = pose_.inverse() * a.pose;
  // A scene that leaves a direction free (the map's first view alone: a standing car's second scan matched 14 of
  // 77 edges and moved 0.5 m) says nothing the prediction does not: keep the constant-velocity motion. The weak
  // prior alone let the few matches pull the pose along the free direction.
  const bool keep_prediction = a.degenerate && cfg_.odometry.hold_degenerate;
  if (keep_prediction) a.pose = predicted, delta = pose_.inverse() * predicted;
  // The deskew used the previous scan's motion; redo it with this scan's own and register again from there. Not
  // with the car's measured motion: that is the scan's own, and the increment also holds the correction of the
  // previous pose's error (a yaw 0.1 rad off, corrected in one scan, reads as 1 rad/s), which deskewed the next
  // scan the other way: the poses alternated ±0.2 m and ±0.05 rad scan by scan.
  for (int pass = 1; pass < cfg_.odometry.deskew_passes && !keep_prediction && !measured; ++pass) {
    velocity_ = twist_of(delta, dt);
    edges = deskew(f.edges, t), planes = deskew(f.planes, t);
    a = registration_.align(edges, planes, map_, a.pose);
    delta = pose_.inverse() * a.pose;
  }
  out.has_increment = true;
  out.increment.t0 = stamp_;
  out.increment.t1 = t;
  out.increment.delta = to_pose2(delta);
  // The map is held fixed: the registration's covariance is the increment's. (x, y, yaw) = indices 0, 1, 5.
  const int ix[3] = {0, 1, 5};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) out.increment.covariance(i, j) = a.covariance(ix[i], ix[j]);
  out.covariance = a.covariance;
  auto& d = out.diagnostics;
  d.edge_matches = a.edge_matches;
  d.plane_matches = a.plane_matches;
  d.iterations = a.iterations;
  d.degenerate = a.degenerate;
  d.degenerate_directions = a.degenerate_directions;
  d.min_information = a.information_eigen[0];
  d.rms = a.rms;

  velocity_ = velocity0 + cfg_.odometry.velocity_gain * (twist_of(delta, dt) - velocity0);
  pose_ = a.pose;
  stamp_ = t;
  const Pose3 since = last_keyframe_.inverse() * pose_;
  const bool keyframe = since.translation().norm() >= cfg_.odometry.keyframe_distance ||
                        Eigen::AngleAxisd(since.linear()).angle() >= cfg_.odometry.keyframe_angle;
  std::vector<Vec3> we, wp;
  we.reserve(edges.size());
  wp.reserve(planes.size());
  for (const auto& p : edges) we.push_back(pose_ * p);
  for (const auto& p : planes) wp.push_back(pose_ * p);
  add_to_map(we, wp, keyframe);
  out.pose = pose_;
  out.stamp = t;
  return out;
}

void LidarOdometry::add_to_map(const std::vector<Vec3>& edges, const std::vector<Vec3>& planes, bool keyframe) {
  last_ = {edges, planes};
  if (keyframe) {
    last_keyframe_ = pose_;
    keyframes_.push_back(last_);
    while (int(keyframes_.size()) > cfg_.odometry.keyframes) keyframes_.pop_front();
  }
  rebuild_map();
}

void LidarOdometry::rebuild_map() {
  // The previous scan first: the voxel filter keeps the first point per voxel, so the freshest view wins.
  std::vector<Vec3> e = last_.edges, p = last_.planes;
  for (auto it = keyframes_.rbegin(); it != keyframes_.rend(); ++it) {
    e.insert(e.end(), it->edges.begin(), it->edges.end());
    p.insert(p.end(), it->planes.begin(), it->planes.end());
  }
  // Edges are few and thin: a finer voxel than the planes so a cone's silhouette keeps its points.
  map_.edges.build(voxel_downsample(e, cfg_.odometry.map_voxel * 0.5));
  map_.planes.build(voxel_downsample(p, cfg_.odometry.map_voxel));
}

}  // namespace fsd::lidar_odometry
