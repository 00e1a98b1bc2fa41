#include "drivers/sim/world/world.hpp"

#include <cmath>
#include <limits>

namespace fsd::sim {

namespace {
// Layers by the top of their bodies above the ground (m) and their grid cells (m), found by benchmark.
constexpr std::array<double, 2> kLayerTop{0.4, std::numeric_limits<double>::infinity()};
constexpr std::array<double, 2> kLayerCell{1.0, 4.0};
constexpr double kPanelPiece = 2.0;         // m: fences enter the grid in short pieces
constexpr double kTyreReflectivity = 6.0;   // black rubber
constexpr double kPostReflectivity = 60.0;  // painted post
constexpr double kFenceReflectivity = 30.0;
constexpr double kRayEpsilon = 1e-9;
}  // namespace

const char* to_string(Surface s) {
  switch (s) {
    case Surface::None:
      return "none";
    case Surface::Ground:
      return "ground";
    case Surface::Grass:
      return "grass";
    case Surface::ConeBody:
      return "cone_body";
    case Surface::ConeStripe:
      return "cone_stripe";
    case Surface::Tyre:
      return "tyre";
    case Surface::Post:
      return "post";
    case Surface::Fence:
      return "fence";
  }
  return "?";
}

World::World(const Track& track, const WorldConfig& cfg, std::uint64_t seed)
    : track_(track),
      cfg_(cfg),
      area_(track),
      ground_(cfg, area_, seed),
      ground_frame_(Eigen::Quaterniond::FromTwoVectors(Vec3::UnitZ(), ground_.normal()).toRotationMatrix()) {
  for (const auto& tc : track.cones) {
    WorldCone c;
    c.base = Vec3(tc.position.x(), tc.position.y(), ground_.height(tc.position.x(), tc.position.y()));
    c.colour = tc.colour;
    c.role = tc.role;
    c.big = tc.role == ConeRole::Timing;
    const ConeShape& shape = cone_shape(c.big);
    c.height = shape.height;
    c.base_width = 2 * shape.base_radius;
    cones_.push_back(c);
  }
  for (int i = 0; i < static_cast<int>(cones_.size()); ++i) bodies_.push_back(cone_body(i));
  distractors_ = place_distractors(area_, cfg, seed);
  for (int i = 0; i < static_cast<int>(distractors_.size()); ++i) add_distractor_bodies(i);
  rebuild_index();
}

World::Body World::cone_body(int index) const {
  const WorldCone& c = cones_[static_cast<std::size_t>(index)];
  const ConeShape& shape = cone_shape(c.big);
  Body b;
  b.cone = index;
  b.a = shape.base_radius;
  b.b = shape.top_radius;
  b.h = shape.height;
  const Pose3 pose = cone_pose(c);
  b.origin = pose.translation();
  b.to_local = pose.linear().transpose();
  finish_body(b);
  return b;
}

Pose3 World::cone_pose(const WorldCone& c) const {
  Pose3 T = Pose3::Identity();
  T.linear() = ground_frame_;
  T.translation() = c.base;
  if (c.knocked) {
    const ConeShape& shape = cone_shape(c.big);
    T.linear() = ground_frame_ * lying_cone_rotation(shape, c.fall_yaw);
    T.translation() = c.base + ground_.normal() * lying_cone_axis_height(shape);
  }
  return T;
}

void World::add_distractor_bodies(int index) {
  const Distractor& d = distractors_[static_cast<std::size_t>(index)];
  const Vec3 base(d.position.x(), d.position.y(), ground_.height(d.position.x(), d.position.y()));
  Body b;
  b.distractor = index;
  switch (d.type) {
    case DistractorType::Tyre:
      b.a = b.b = d.radius;
      if (d.standing) {
        // Axle horizontal along yaw: the cylinder's axis runs from one sidewall to the other.
        const Eigen::Matrix3d to_map = ground_frame_ * (Eigen::AngleAxisd(d.yaw, Vec3::UnitZ()) *
                                                        Eigen::AngleAxisd(std::numbers::pi / 2, Vec3::UnitY()))
                                                           .toRotationMatrix();
        b.to_local = to_map.transpose();
        b.origin = base + ground_.normal() * d.radius - to_map.col(2) * (d.width / 2);
        b.h = d.width;
      } else {
        b.to_local = ground_frame_.transpose();
        b.origin = base;
        b.h = d.width;
      }
      break;
    case DistractorType::TyreStack:
    case DistractorType::Post:
      b.a = b.b = d.radius;
      b.h = d.height;
      b.to_local = ground_frame_.transpose();
      b.origin = base;
      break;
    case DistractorType::Fence: {
      b.shape = Body::Shape::Panel;
      const Eigen::Matrix3d to_map = ground_frame_ * Eigen::AngleAxisd(d.yaw, Vec3::UnitZ()).toRotationMatrix();
      b.to_local = to_map.transpose();
      b.h = d.height;
      const int pieces = std::max(1, static_cast<int>(std::ceil(d.length / kPanelPiece)));
      const double piece = d.length / pieces;
      for (int k = 0; k < pieces; ++k) {
        Body p = b;
        const Vec2 start = d.position + (k * piece) * Vec2(std::cos(d.yaw), std::sin(d.yaw));
        p.origin = Vec3(start.x(), start.y(), ground_.height(start.x(), start.y()));
        p.a = piece;
        finish_body(p);
        bodies_.push_back(p);
      }
      return;
    }
  }
  finish_body(b);
  bodies_.push_back(b);
}

void World::finish_body(Body& b) const {
  const Eigen::Matrix3d to_map = b.to_local.transpose();
  if (b.shape == Body::Shape::Panel) {
    b.centre = b.origin + to_map * Vec3(b.a / 2, 0, b.h / 2);
    b.bound_radius = std::hypot(b.a / 2, b.h / 2);
  } else {
    b.centre = b.origin + to_map * Vec3(0, 0, b.h / 2);
    b.bound_radius = std::hypot(std::max(b.a, b.b), b.h / 2);
  }
}

Eigen::AlignedBox3d World::bounds(const Body& b) const {
  const Eigen::Matrix3d to_map = b.to_local.transpose();
  Eigen::AlignedBox3d box;
  if (b.shape == Body::Shape::Panel) {
    for (double x : {0.0, b.a})
      for (double z : {0.0, b.h}) box.extend(b.origin + to_map * Vec3(x, 0, z));
    return box;
  }
  // A disc of radius r and unit normal n spans r·sqrt(1 − n_i²) about its centre along axis i.
  const Vec3 axis = to_map.col(2);
  const Vec3 spread = (Vec3::Ones() - axis.cwiseAbs2()).cwiseMax(0.0).cwiseSqrt();
  for (const auto& [centre, r] : {std::pair{b.origin, b.a}, std::pair{Vec3(b.origin + axis * b.h), b.b}}) {
    box.extend(centre - r * spread);
    box.extend(centre + r * spread);
  }
  return box;
}

void World::rebuild_index() {
  std::array<std::vector<Eigen::AlignedBox2d>, kLayerTop.size()> boxes;
  std::array<std::vector<std::uint32_t>, kLayerTop.size()> ids;
  for (auto& layer : layers_) layer.max_height = 0;
  for (std::uint32_t i = 0; i < bodies_.size(); ++i) {
    const auto box = bounds(bodies_[i]);
    double ground_low = std::numeric_limits<double>::infinity();
    for (double x : {box.min().x(), box.max().x()})
      for (double y : {box.min().y(), box.max().y()}) ground_low = std::min(ground_low, ground_.height(x, y));
    const double top = box.max().z() - ground_low;
    std::size_t l = 0;
    while (top > kLayerTop[l]) ++l;
    boxes[l].emplace_back(box.min().head<2>(), box.max().head<2>());
    ids[l].push_back(i);
    layers_[l].max_height = std::max(layers_[l].max_height, top);
  }
  for (std::size_t l = 0; l < layers_.size(); ++l) layers_[l].grid.build(boxes[l], ids[l], kLayerCell[l]);
}

std::optional<RayHit> World::raycast(const Vec3& origin, const Vec3& dir, double max_range, const Beam& beam) const {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  // Height above the ground along the ray is linear in t: h(t) = h0 + t·hd.
  const double h0 = origin.z() - ground_.height(origin.x(), origin.y());
  const double hd = dir.z() - ground_.slope_x() * dir.x() - ground_.slope_y() * dir.y();
  if (h0 < 0.0 || !(max_range > 0.0)) return std::nullopt;
  const double t_ground = hd < 0.0 ? -h0 / hd : kInf;

  const Body* best_body = nullptr;
  LocalHit best{};
  double best_t = std::min(max_range, t_ground);
  for (const auto& layer : layers_) {
    // The layer's bodies can only be hit while the ray is between the ground and the layer's tallest body.
    double t_begin = 0.0, t_end = best_t;
    if (h0 > layer.max_height) t_begin = hd < 0.0 ? (layer.max_height - h0) / hd : kInf;
    if (hd > 0.0) t_end = std::min(t_end, (layer.max_height - h0) / hd);
    if (t_begin > t_end) continue;
    layer.grid.traverse(origin.head<2>(), dir.head<2>(), t_begin, t_end,
                        [&](std::span<const std::uint32_t> items, double t_exit) {
                          for (const auto idx : items) {
                            const Body& b = bodies_[idx];
                            // Bounding sphere first.
                            const Vec3 v = b.centre - origin;
                            const double tc = v.dot(dir);
                            if (v.squaredNorm() - tc * tc > b.bound_radius * b.bound_radius) continue;
                            if (tc + b.bound_radius < kRayEpsilon || tc - b.bound_radius > best_t) continue;
                            const Vec3 o = b.to_local * (origin - b.origin);
                            const Vec3 d = b.to_local * dir;
                            const auto hit = b.shape == Body::Shape::Panel
                                                 ? intersect_panel(o, d, b.a, b.h, kRayEpsilon, best_t)
                                                 : intersect_frustum(o, d, b.a, b.b, b.h, kRayEpsilon, best_t);
                            if (hit) {
                              best = *hit;
                              best_t = hit->t;
                              best_body = &b;
                            }
                          }
                          return best_body != nullptr && best_t <= t_exit;
                        });
  }
  if (best_body) return describe_hit(*best_body, best, origin, dir, beam);
  if (t_ground > max_range) return std::nullopt;
  RayHit g;
  g.distance = t_ground;
  g.point = origin + t_ground * dir;
  g.normal = ground_.normal();
  g.surface = ground_.surface(g.point.x(), g.point.y());
  g.reflectivity = ground_.reflectivity(g.point.x(), g.point.y(), g.surface);
  return g;
}

RayHit World::describe_hit(const Body& b, const LocalHit& hit, const Vec3& origin, const Vec3& dir,
                           const Beam& beam) const {
  RayHit r;
  r.distance = hit.t;
  r.point = origin + hit.t * dir;
  r.normal = b.to_local.transpose() * hit.normal;
  r.cone = b.cone;
  r.distractor = b.distractor;
  if (b.cone >= 0) {
    const WorldCone& c = cones_[static_cast<std::size_t>(b.cone)];
    const ConeShape& shape = cone_shape(c.big);
    const bool stripe = shape.in_stripe(hit.point.z());
    const ConePaint paint = cone_paint(c.colour);
    r.surface = stripe ? Surface::ConeStripe : Surface::ConeBody;
    const double half = (beam.aperture + beam.divergence * hit.t) / 2;
    const double share = half > 0 ? shape.stripe_share(hit.point.z() - half, hit.point.z() + half) : stripe;
    r.reflectivity = paint.body + share * (paint.stripe - paint.body);
  } else {
    switch (distractors_[static_cast<std::size_t>(b.distractor)].type) {
      case DistractorType::Tyre:
      case DistractorType::TyreStack:
        r.surface = Surface::Tyre;
        r.reflectivity = kTyreReflectivity;
        break;
      case DistractorType::Post:
        r.surface = Surface::Post;
        r.reflectivity = kPostReflectivity;
        break;
      case DistractorType::Fence:
        r.surface = Surface::Fence;
        r.reflectivity = kFenceReflectivity;
        break;
    }
  }
  return r;
}

int World::update_hits(std::span<const Vec2> footprint, Stamp t) {
  if (footprint.size() < 3) return 0;
  Vec2 centroid = Vec2::Zero();
  for (const auto& p : footprint) centroid += p;
  centroid /= static_cast<double>(footprint.size());
  int newly = 0;
  for (int i = 0; i < static_cast<int>(cones_.size()); ++i) {
    WorldCone& c = cones_[static_cast<std::size_t>(i)];
    if (c.knocked || !polygon_touches_disc(footprint, c.base.head<2>(), c.base_width / 2)) continue;
    c.knocked = true;
    c.hit_time = t;
    const Vec2 away = c.base.head<2>() - centroid;
    c.fall_yaw = std::atan2(away.y(), away.x());
    bodies_[static_cast<std::size_t>(i)] = cone_body(i);
    ++newly;
  }
  if (newly > 0) {
    hits_ += newly;
    rebuild_index();
  }
  return newly;
}

}  // namespace fsd::sim
