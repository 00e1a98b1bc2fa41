#include "drivers/sim/sensors/camera_model_scene.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <opencv2/imgproc.hpp>

#include "drivers/sim/world/cone_geometry.hpp"

namespace fsd::sim {

namespace {
// Albedos (B, G, R) chosen so that saturated FS cone colours keep their hue under the exposure range.
const cv::Vec3d kBlue(185, 75, 30);
const cv::Vec3d kYellow(25, 215, 230);
const cv::Vec3d kOrange(20, 95, 240);
const cv::Vec3d kRed(35, 30, 200);
const cv::Vec3d kWhite(225, 225, 225);
const cv::Vec3d kBlack(35, 35, 35);
const cv::Vec3d kGrey(128, 128, 128);
const cv::Vec3d kRubber(38, 38, 40);
const cv::Vec3d kRubberGap(18, 18, 18);
const cv::Vec3d kPost(170, 172, 168);
const cv::Vec3d kPostCap(90, 90, 90);
const cv::Vec3d kFenceBanner(45, 95, 40);
const cv::Vec3d kFenceRail(150, 150, 150);
constexpr double kInteriorDarkening = 0.25;  // inside of a hollow cone or a tyre
constexpr double kTyreHole = 0.58;           // rim diameter / tyre diameter
constexpr double kStackGap = 0.015;          // m of dark groove between stacked tyres
constexpr double kFenceRailShare = 0.1;      // top part of a fence panel that is the rail
constexpr double kFencePiece = 2.0;          // m: fences are drawn in pieces for the depth sort

struct ConePaintColours {
  cv::Vec3d body, stripe;
};

ConePaintColours cone_colours(ConeColour c) {
  switch (c) {
    case ConeColour::Blue:
      return {kBlue, kWhite};
    case ConeColour::Yellow:
      return {kYellow, kBlack};
    case ConeColour::Orange:
    case ConeColour::BigOrange:
      return {kOrange, kWhite};
    case ConeColour::Red:
      return {kRed, kWhite};
    case ConeColour::Unknown:
      break;
  }
  return {kGrey, kWhite};
}

Vec3 ground_point(const World& world, const Vec2& p) { return {p.x(), p.y(), world.ground_height(p.x(), p.y())}; }

// Facets around the axis for a body of this apparent radius (px): enough for a smooth silhouette, few for specks.
int facet_count(double radius_px) { return std::clamp(static_cast<int>(radius_px * 0.7) + 6, 6, 28); }

struct Item {
  double depth;
  int object;
  const Solid* solid;
  const Panel* panel;
};
}  // namespace

void Solid::add_band(double z0, double z1, const cv::Vec3d& albedo) {
  if (z1 <= z0 || band_count >= static_cast<int>(bands.size())) return;
  bands[static_cast<std::size_t>(band_count++)] = {z0, z1, albedo};
}

Solid cone_solid(const World& world, int index) {
  const WorldCone& c = world.cones()[static_cast<std::size_t>(index)];
  const ConeShape& shape = cone_shape(c.big);
  const ConePaintColours paint = cone_colours(c.colour);
  Solid s;
  s.r0 = shape.base_radius;
  s.r1 = shape.top_radius;
  s.h = shape.height;
  const Pose3 pose = world.cone_pose(c);  // as World places the body, upright or fallen
  s.to_map = pose.linear();
  s.origin = pose.translation();
  double z = 0.0;
  for (int i = 0; i < shape.stripe_count; ++i) {
    const auto& band = shape.stripes[static_cast<std::size_t>(i)];
    s.add_band(z, band[0] * s.h, paint.body);
    s.add_band(band[0] * s.h, band[1] * s.h, paint.stripe);
    z = band[1] * s.h;
  }
  s.add_band(z, s.h, paint.body);
  s.top_albedo = paint.body;
  s.bottom_albedo = paint.body * kInteriorDarkening;  // the hollow inside of a fallen cone
  return s;
}

std::vector<Solid> distractor_solids(const World& world, int index) {
  const Distractor& d = world.distractors()[static_cast<std::size_t>(index)];
  const Eigen::Matrix3d& frame = world.ground_frame();
  const Vec3 base = ground_point(world, d.position);
  Solid s;
  s.to_map = frame;
  s.origin = base;
  s.r0 = s.r1 = d.radius;
  switch (d.type) {
    case DistractorType::Tyre:
      s.h = d.width;
      if (d.standing) {  // axle horizontal along yaw, as World places it
        s.to_map =
            frame * (Eigen::AngleAxisd(d.yaw, Vec3::UnitZ()) * Eigen::AngleAxisd(std::numbers::pi / 2, Vec3::UnitY()))
                        .toRotationMatrix();
        s.origin = base + world.ground_normal() * d.radius - s.to_map.col(2) * (d.width / 2);
      }
      s.add_band(0, s.h, kRubber);
      s.top_albedo = s.bottom_albedo = kRubber;
      s.hole = kTyreHole;
      s.inner_albedo = kRubber * kInteriorDarkening;
      break;
    case DistractorType::TyreStack: {
      s.h = d.height;
      const int n = std::clamp(d.tyre_count, 1, 5);
      const double w = s.h / n;
      for (int i = 0; i < n; ++i) {
        const double z0 = i * w, z1 = (i + 1) * w;
        s.add_band(z0, z1 - (i + 1 < n ? kStackGap : 0.0), kRubber);
        if (i + 1 < n) s.add_band(z1 - kStackGap, z1, kRubberGap);
      }
      s.top_albedo = s.bottom_albedo = kRubber;
      s.hole = kTyreHole;
      s.inner_albedo = kRubber * kInteriorDarkening;
      break;
    }
    case DistractorType::Post:
      s.h = d.height;
      s.add_band(0, s.h, kPost);
      s.top_albedo = s.bottom_albedo = kPostCap;
      break;
    case DistractorType::Fence:
      return {};
  }
  return {s};
}

std::vector<Panel> fence_panels(const World& world, int index) {
  const Distractor& d = world.distractors()[static_cast<std::size_t>(index)];
  if (d.type != DistractorType::Fence) return {};
  std::vector<Panel> panels;
  const Vec3 up = world.ground_normal();
  const Vec2 dir(std::cos(d.yaw), std::sin(d.yaw));
  const int pieces = std::max(1, static_cast<int>(std::ceil(d.length / kFencePiece)));
  const double piece = d.length / pieces;
  const double banner = d.height * (1.0 - kFenceRailShare);
  for (int k = 0; k < pieces; ++k) {
    const Vec3 a = ground_point(world, d.position + (k * piece) * dir);
    const Vec3 b = ground_point(world, d.position + ((k + 1) * piece) * dir);
    panels.push_back({{a, b, b + up * banner, a + up * banner}, kFenceBanner});
    panels.push_back({{a + up * banner, b + up * banner, b + up * d.height, a + up * d.height}, kFenceRail});
  }
  return panels;
}

SceneBuilder::SceneBuilder(const World& world, const Sunlight& sun) : world_(world), sun_(sun) {
  for (int i = 0; i < static_cast<int>(world.distractors().size()); ++i) {
    distractor_solids_.push_back(distractor_solids(world, i));
    fences_.push_back(fence_panels(world, i));
  }
}

void SceneBuilder::build(const CameraView& view, const cv::Scalar& gains, bool with_shadows, DisplayList& list) const {
  list.clear();
  const int cones = static_cast<int>(world_.cones().size());
  std::vector<Solid> solids;
  std::vector<int> solid_objects;
  solids.reserve(world_.cones().size() + world_.distractors().size());
  for (int i = 0; i < cones; ++i) {
    solids.push_back(cone_solid(world_, i));
    solid_objects.push_back(i);
  }
  for (std::size_t j = 0; j < distractor_solids_.size(); ++j)
    for (const auto& s : distractor_solids_[j]) {
      solids.push_back(s);
      solid_objects.push_back(cones + static_cast<int>(j));
    }

  // Shadows reach past their body, so they are culled with a wider sphere.
  constexpr double kShadowReach = 2.5;
  std::vector<Item> items;
  for (std::size_t i = 0; i < solids.size(); ++i) {
    const Solid& s = solids[i];
    const Vec3 c = s.centre();
    if (with_shadows && view.may_see(c, s.bound_radius() * kShadowReach + 0.5))
      emit_solid_shadow(view, s, solid_objects[i], list);
    if (view.may_see(c, s.bound_radius()))
      items.push_back({(c - view.position()).norm(), solid_objects[i], &s, nullptr});
  }
  for (std::size_t j = 0; j < fences_.size(); ++j)
    for (const auto& p : fences_[j]) {
      const Vec3 c = (p.corners[0] + p.corners[2]) / 2;
      const double r = (p.corners[2] - p.corners[0]).norm() / 2;
      if (!view.may_see(c, r * kShadowReach)) continue;
      if (with_shadows) emit_shadow(view, {p.corners.begin(), p.corners.end()}, cones + static_cast<int>(j), list);
      if (view.may_see(c, r)) items.push_back({(c - view.position()).norm(), cones + static_cast<int>(j), nullptr, &p});
    }

  std::stable_sort(items.begin(), items.end(), [](const Item& a, const Item& b) { return a.depth > b.depth; });
  for (const auto& it : items) {
    if (it.solid)
      emit_solid(view, *it.solid, gains, it.object, it.depth, list);
    else
      emit_panel(view, *it.panel, gains, it.object, list);
  }
}

void SceneBuilder::emit_solid(const CameraView& view, const Solid& s, const cv::Scalar& gains, int object, double depth,
                              DisplayList& list) const {
  const int n = facet_count(view.intrinsics().fx * std::max(s.r0, s.r1) / std::max(depth, 0.1));
  const Eigen::Matrix3d M = view.rotation() * s.to_map;  // body → camera
  const Vec3 o = view.to_camera(s.origin);
  auto cam = [&](double r, double a, double z) { return Vec3(M * Vec3(r * std::cos(a), r * std::sin(a), z) + o); };
  const Vec3 eye = s.to_map.transpose() * (view.position() - s.origin);  // camera in the body frame
  const double slope = (s.r0 - s.r1) / s.h;
  const double step = 2.0 * std::numbers::pi / n;
  std::array<Vec3, 4> quad;

  auto facet_faces_eye = [&](double mid, double r, double sign) {
    const Vec3 normal = Vec3(std::cos(mid), std::sin(mid), slope).normalized() * sign;
    const Vec3 p(r * std::cos(mid), r * std::sin(mid), s.h / 2);
    return std::pair{(eye - p).dot(normal) > 0.0, normal};
  };

  // A ring's inner wall first: the far side of it shows through the hole.
  if (s.hole > 0.0) {
    const double ri0 = s.r0 * s.hole, ri1 = s.r1 * s.hole;
    for (int k = 0; k < n; ++k) {
      const double a0 = k * step, a1 = a0 + step, mid = a0 + step / 2;
      const auto [faces, normal] = facet_faces_eye(mid, (ri0 + ri1) / 2, -1.0);
      if (!faces) continue;
      quad = {cam(ri0, a0, 0), cam(ri0, a1, 0), cam(ri1, a1, s.h), cam(ri1, a0, s.h)};
      view.add_polygon(quad, Sunlight::lit(s.inner_albedo, sun_.shade(s.to_map * normal), gains), object, list);
    }
  }
  // Outer facets facing the camera, band by band.
  for (int k = 0; k < n; ++k) {
    const double a0 = k * step, a1 = a0 + step, mid = a0 + step / 2;
    const auto [faces, normal] = facet_faces_eye(mid, (s.r0 + s.r1) / 2, 1.0);
    if (!faces) continue;
    const double brightness = sun_.shade(s.to_map * normal);
    for (int b = 0; b < s.band_count; ++b) {
      const Band& band = s.bands[static_cast<std::size_t>(b)];
      const double q0 = s.r0 - slope * band.z0, q1 = s.r0 - slope * band.z1;
      quad = {cam(q0, a0, band.z0), cam(q0, a1, band.z0), cam(q1, a1, band.z1), cam(q1, a0, band.z1)};
      view.add_polygon(quad, Sunlight::lit(band.albedo, brightness, gains), object, list);
    }
  }
  // Caps facing the camera: discs, or rings of quads around a hole.
  auto cap = [&](double z, double r, const cv::Vec3d& albedo, const Vec3& normal) {
    if (r <= 0.0) return;
    const cv::Scalar colour = Sunlight::lit(albedo, sun_.shade(s.to_map * normal), gains);
    if (s.hole > 0.0) {
      for (int k = 0; k < n; ++k) {
        const double a0 = k * step, a1 = a0 + step;
        quad = {cam(r, a0, z), cam(r, a1, z), cam(r * s.hole, a1, z), cam(r * s.hole, a0, z)};
        view.add_polygon(quad, colour, object, list);
      }
      return;
    }
    std::array<Vec3, 32> disc;
    for (int k = 0; k < n; ++k) disc[static_cast<std::size_t>(k)] = cam(r, k * step, z);
    view.add_polygon(std::span(disc.data(), static_cast<std::size_t>(n)), colour, object, list);
  };
  if (eye.z() > s.h) cap(s.h, s.r1, s.top_albedo, Vec3::UnitZ());
  if (eye.z() < 0.0) cap(0.0, s.r0, s.bottom_albedo, -Vec3::UnitZ());
}

void SceneBuilder::emit_panel(const CameraView& view, const Panel& p, const cv::Scalar& gains, int object,
                              DisplayList& list) const {
  const Vec3 normal = (p.corners[1] - p.corners[0]).cross(p.corners[3] - p.corners[0]).normalized();
  std::array<Vec3, 4> quad;
  for (std::size_t i = 0; i < 4; ++i) quad[i] = view.to_camera(p.corners[i]);
  view.add_polygon(quad, Sunlight::lit(p.albedo, sun_.shade_two_sided(normal), gains), object, list);
}

void SceneBuilder::emit_solid_shadow(const CameraView& view, const Solid& s, int object, DisplayList& list) const {
  constexpr int kRim = 12;
  std::vector<Vec3> points;
  for (int k = 0; k < kRim; ++k) {
    const double a = 2.0 * std::numbers::pi * k / kRim;
    points.push_back(s.origin + s.to_map * Vec3(s.r0 * std::cos(a), s.r0 * std::sin(a), 0.0));
    points.push_back(s.origin + s.to_map * Vec3(s.r1 * std::cos(a), s.r1 * std::sin(a), s.h));
  }
  emit_shadow(view, points, object, list);
}

void SceneBuilder::emit_shadow(const CameraView& view, const std::vector<Vec3>& points, int object,
                               DisplayList& list) const {
  // The ground is the plane n·X = 0 (z = sx·x + sy·y); a point casts its shadow along −sun onto it.
  const Vec3 n = world_.ground_normal();
  const Vec3& sun = sun_.direction();
  const double ns = n.dot(sun);
  if (ns <= 0.05) return;  // sun at or below the ground's horizon
  std::vector<cv::Point2f> flat;
  for (const auto& p : points) {
    const Vec3 q = p - sun * (std::max(0.0, n.dot(p)) / ns);
    flat.emplace_back(static_cast<float>(q.x()), static_cast<float>(q.y()));
  }
  std::vector<cv::Point2f> hull;
  cv::convexHull(flat, hull);
  std::vector<Vec3> poly;
  for (const auto& h : hull) poly.push_back(view.to_camera(ground_point(world_, Vec2(h.x, h.y))));
  view.add_polygon(poly, cv::Scalar::all(0), object, list, true);
}

}  // namespace fsd::sim
