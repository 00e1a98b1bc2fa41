#pragma once
// Shapes of the virtual world with analytic ray intersection, in the shape's own frame (z up along the axis,
// origin at the centre of the base). Cones are circular frustums; cylinders (tyres, posts) are frustums with equal
// radii; a fence is a vertical rectangle (panel).
//
// Cone dimensions follow the FSG/FS rules: small cone 228 × 228 × 325 mm, big orange cone 285 × 285 × 505 mm. The
// body is modelled as a frustum whose base diameter is the cone's base width (the square base plate, ~1 cm high and
// hardly ever hit by a LiDAR beam, is left out) and whose top is the cone's narrow tip.
#include <array>
#include <optional>
#include <span>

#include "common/geometry.hpp"
#include "common/types.hpp"

namespace fsd::sim {

struct ConeShape {
  double base_radius;
  double top_radius;
  double height;
  // Height bands (fractions of the height, lower and upper) painted in the stripe colour.
  std::array<std::array<double, 2>, 2> stripes;
  int stripe_count;

  double radius_at(double z) const { return base_radius - (base_radius - top_radius) * z / height; }
  bool in_stripe(double z) const;
  // Share of the height span [z_lo, z_hi] painted in the stripe colour (z_lo < z_hi; parts off the cone count as
  // body: the beam's edge beyond the tip or the base lands on another surface, taken as the body's level).
  double stripe_share(double z_lo, double z_hi) const;
};

inline constexpr ConeShape kSmallCone{0.114, 0.025, 0.325, {{{0.38, 0.62}, {0.0, 0.0}}}, 1};
inline constexpr ConeShape kBigCone{0.1425, 0.03, 0.505, {{{0.28, 0.40}, {0.58, 0.70}}}, 2};

const ConeShape& cone_shape(bool big);

// Calibrated VLP-16 reflectivity (0..100 diffuse, 101..255 retro-reflective) of a cone's body and stripe paint.
// FSG blue cones carry a white stripe and yellow ones a black stripe, so the stripe is brighter than the body on
// blue and darker on yellow: the intensity pattern a LiDAR-only colour estimate uses. Orange cones: white stripes.
struct ConePaint {
  double body;
  double stripe;
};
ConePaint cone_paint(ConeColour colour);

// A ray hit in the shape's frame.
struct LocalHit {
  double t;  // ray parameter (distance for a unit direction)
  Vec3 point;
  Vec3 normal;  // outward unit normal
};

// Nearest intersection with t in (t_min, t_max) of o + t·d with the closed frustum: side x² + y² = ρ(z)²,
// ρ(z) = r0 − (r0 − r1)·z/h for 0 ≤ z ≤ h, plus the discs at z = 0 (radius r0) and z = h (radius r1).
std::optional<LocalHit> intersect_frustum(const Vec3& o, const Vec3& d, double r0, double r1, double h, double t_min,
                                          double t_max);

// Nearest intersection with the two-sided rectangle y = 0, 0 ≤ x ≤ length, 0 ≤ z ≤ height.
std::optional<LocalHit> intersect_panel(const Vec3& o, const Vec3& d, double length, double height, double t_min,
                                        double t_max);

// Rotation (shape frame → ground-aligned frame) of a cone lying on its side with its tip pointing along yaw:
// the axis dips by the half-angle so that one generator lies on the ground. The base centre then sits
// base_radius·cos(half-angle) above the ground.
Eigen::Matrix3d lying_cone_rotation(const ConeShape& shape, double yaw);
double lying_cone_axis_height(const ConeShape& shape);

// Whether a closed polygon (any orientation, not self-intersecting) and a disc overlap.
bool polygon_touches_disc(std::span<const Vec2> polygon, const Vec2& centre, double radius);

}  // namespace fsd::sim
