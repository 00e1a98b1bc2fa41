#pragma once
// The virtual camera's scene: the world's cones and distractors as shaded polygon meshes, sorted far to near
// (painter's algorithm) into a DisplayList for one view.
//
// Cones, tyres, tyre stacks and posts are frustums (cylinders have equal radii) cut into facets around the axis
// and into painted bands along it (a cone's stripes, a stack's tyres); only the facets facing the camera are drawn,
// so a body never overdraws itself. Tyres are rings: through the hole one sees the inner wall and what lies behind.
// Fence segments are flat panels. Every object casts a hard shadow on the ground plane: the convex hull of its
// vertices pushed along the sun direction.
#include <array>
#include <vector>

#include <opencv2/core/types.hpp>

#include "drivers/sim/sensors/camera_model_lighting.hpp"
#include "drivers/sim/sensors/camera_model_view.hpp"
#include "drivers/sim/world/world.hpp"

namespace fsd::sim {

// One painted section of a frustum between heights z0 and z1 along its axis.
struct Band {
  double z0 = 0, z1 = 0;
  cv::Vec3d albedo;  // B, G, R on 0..255
};

// A frustum in its own frame (z along the axis, origin at the centre of the base) placed in the map.
struct Solid {
  Eigen::Matrix3d to_map = Eigen::Matrix3d::Identity();
  Vec3 origin = Vec3::Zero();
  double r0 = 0, r1 = 0, h = 0;
  std::array<Band, 10> bands{};
  int band_count = 0;
  cv::Vec3d top_albedo, bottom_albedo;
  double hole = 0.0;  // inner radius / outer radius of a ring (tyres); 0 = solid caps
  cv::Vec3d inner_albedo;

  void add_band(double z0, double z1, const cv::Vec3d& albedo);
  Vec3 centre() const { return origin + to_map * Vec3(0, 0, h / 2); }
  double bound_radius() const { return std::hypot(std::max(r0, r1), h / 2); }
};

// A flat convex quadrilateral (a fence panel piece), corners in the map.
struct Panel {
  std::array<Vec3, 4> corners;
  cv::Vec3d albedo;
};

// The solids the world's cone and distractor stand for (fences have none).
Solid cone_solid(const World& world, int cone);
std::vector<Solid> distractor_solids(const World& world, int distractor);
std::vector<Panel> fence_panels(const World& world, int distractor);

class SceneBuilder {
 public:
  SceneBuilder(const World& world, const Sunlight& sun);

  // Fills `list` with every object the view may see, far to near, lit by the sun and the exposure gains; with
  // shadows, also each object's shadow polygon on the ground (darkening is applied by the painter).
  void build(const CameraView& view, const cv::Scalar& gains, bool with_shadows, DisplayList& list) const;

  int object_count() const { return static_cast<int>(world_.cones().size() + world_.distractors().size()); }

 private:
  void emit_solid(const CameraView& view, const Solid& s, const cv::Scalar& gains, int object, double depth,
                  DisplayList& list) const;
  void emit_solid_shadow(const CameraView& view, const Solid& s, int object, DisplayList& list) const;
  void emit_panel(const CameraView& view, const Panel& p, const cv::Scalar& gains, int object, DisplayList& list) const;
  void emit_shadow(const CameraView& view, const std::vector<Vec3>& points, int object, DisplayList& list) const;

  const World& world_;
  const Sunlight& sun_;
  // Distractors never move: their meshes are made once, per distractor.
  std::vector<std::vector<Solid>> distractor_solids_;
  std::vector<std::vector<Panel>> fences_;
};

}  // namespace fsd::sim
