#include "drivers/sim/world/cone_geometry.hpp"

#include <algorithm>
#include <cmath>

namespace fsd::sim {

bool ConeShape::in_stripe(double z) const {
  const double f = z / height;
  for (int i = 0; i < stripe_count; ++i)
    if (f >= stripes[static_cast<std::size_t>(i)][0] && f <= stripes[static_cast<std::size_t>(i)][1]) return true;
  return false;
}

double ConeShape::stripe_share(double z_lo, double z_hi) const {
  if (!(z_hi > z_lo)) return in_stripe(z_lo) ? 1.0 : 0.0;
  double painted = 0;
  for (int i = 0; i < stripe_count; ++i) {
    const auto& s = stripes[static_cast<std::size_t>(i)];
    painted += std::max(0.0, std::min(z_hi, s[1] * height) - std::max(z_lo, s[0] * height));
  }
  return painted / (z_hi - z_lo);
}

const ConeShape& cone_shape(bool big) { return big ? kBigCone : kSmallCone; }

ConePaint cone_paint(ConeColour colour) {
  switch (colour) {
    case ConeColour::Blue:
      return {22.0, 95.0};  // dark blue plastic, white stripe
    case ConeColour::Yellow:
      return {70.0, 8.0};  // bright yellow plastic, black stripe
    case ConeColour::Orange:
    case ConeColour::BigOrange:
      return {55.0, 95.0};  // orange, white stripes
    case ConeColour::Red:
      return {45.0, 95.0};  // FSAC red, white stripe
    case ConeColour::Unknown:
      break;
  }
  return {40.0, 40.0};
}

std::optional<LocalHit> intersect_frustum(const Vec3& o, const Vec3& d, double r0, double r1, double h, double t_min,
                                          double t_max) {
  std::optional<LocalHit> best;
  const double k = (r0 - r1) / h;  // radius lost per metre of height
  auto consider_side = [&](double t) {
    if (!(t > t_min && t < t_max) || (best && t >= best->t)) return;
    const Vec3 p = o + t * d;
    if (p.z() < 0.0 || p.z() > h) return;
    const double rho = r0 - k * p.z();
    const Vec3 n(p.x(), p.y(), k * rho);  // gradient of x² + y² − ρ(z)²
    best = LocalHit{t, p, n.normalized()};
  };
  // Side: (ox + t dx)² + (oy + t dy)² = (A − k dz t)², A = r0 − k oz.
  const double A = r0 - k * o.z();
  const double a = d.x() * d.x() + d.y() * d.y() - k * k * d.z() * d.z();
  const double b = 2.0 * (o.x() * d.x() + o.y() * d.y() + A * k * d.z());
  const double c = o.x() * o.x() + o.y() * o.y() - A * A;
  if (std::abs(a) > 1e-12) {
    const double disc = b * b - 4.0 * a * c;
    if (disc >= 0.0) {
      const double s = std::sqrt(disc);
      // Numerically stable pair of roots.
      const double q = -0.5 * (b + std::copysign(s, b));
      if (q != 0.0) {
        consider_side(q / a);
        consider_side(c / q);
      } else {
        consider_side(0.0);
      }
    }
  } else if (std::abs(b) > 1e-12) {
    consider_side(-c / b);  // ray parallel to a generator: one crossing
  }
  auto consider_disc = [&](double z, double r, double nz) {
    if (std::abs(d.z()) < 1e-12) return;
    const double t = (z - o.z()) / d.z();
    if (!(t > t_min && t < t_max) || (best && t >= best->t)) return;
    const Vec3 p = o + t * d;
    if (p.x() * p.x() + p.y() * p.y() > r * r) return;
    best = LocalHit{t, p, Vec3(0, 0, nz)};
  };
  consider_disc(h, r1, 1.0);
  consider_disc(0.0, r0, -1.0);
  return best;
}

std::optional<LocalHit> intersect_panel(const Vec3& o, const Vec3& d, double length, double height, double t_min,
                                        double t_max) {
  if (std::abs(d.y()) < 1e-12) return std::nullopt;
  const double t = -o.y() / d.y();
  if (!(t > t_min && t < t_max)) return std::nullopt;
  const Vec3 p = o + t * d;
  if (p.x() < 0.0 || p.x() > length || p.z() < 0.0 || p.z() > height) return std::nullopt;
  return LocalHit{t, p, Vec3(0.0, d.y() > 0 ? -1.0 : 1.0, 0.0)};
}

double lying_cone_axis_height(const ConeShape& shape) {
  const double half_angle = std::atan2(shape.base_radius - shape.top_radius, shape.height);
  return shape.base_radius * std::cos(half_angle);
}

Eigen::Matrix3d lying_cone_rotation(const ConeShape& shape, double yaw) {
  // Tilting the axis from +z past horizontal by the half-angle θ (rotation about y by 90° + θ) makes the generator
  // on the +x side horizontal, at the lowest point of the body; yaw then turns the tip to its direction.
  const double half_angle = std::atan2(shape.base_radius - shape.top_radius, shape.height);
  return (Eigen::AngleAxisd(yaw, Vec3::UnitZ()) * Eigen::AngleAxisd(std::numbers::pi / 2 + half_angle, Vec3::UnitY()))
      .toRotationMatrix();
}

namespace {
double distance_to_segment(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 ab = b - a;
  const double len2 = ab.squaredNorm();
  const double s = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (a + s * ab - p).norm();
}
}  // namespace

bool polygon_touches_disc(std::span<const Vec2> polygon, const Vec2& centre, double radius) {
  if (polygon.empty()) return false;
  bool inside = false;
  for (std::size_t i = 0, j = polygon.size() - 1; i < polygon.size(); j = i++) {
    const Vec2& a = polygon[i];
    const Vec2& b = polygon[j];
    if (distance_to_segment(centre, a, b) <= radius) return true;
    if ((a.y() > centre.y()) != (b.y() > centre.y()) &&
        centre.x() < (b.x() - a.x()) * (centre.y() - a.y()) / (b.y() - a.y()) + a.x())
      inside = !inside;
  }
  return inside;
}

}  // namespace fsd::sim
