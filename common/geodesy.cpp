#include "common/geodesy.hpp"

#include <cmath>

namespace fsd {

Vec3 geodetic_to_ecef(const Geodetic& g, const Ellipsoid& e) {
  const double sl = std::sin(g.lat), cl = std::cos(g.lat);
  const double n = e.a / std::sqrt(1.0 - e.e2() * sl * sl);  // prime vertical radius of curvature
  return {(n + g.h) * cl * std::cos(g.lon), (n + g.h) * cl * std::sin(g.lon), (n * (1.0 - e.e2()) + g.h) * sl};
}

Geodetic ecef_to_geodetic(const Vec3& p, const Ellipsoid& e) {
  const double e2 = e.e2();
  const double rho = std::hypot(p.x(), p.y());
  Geodetic g;
  g.lon = std::atan2(p.y(), p.x());
  // Fixed point of lat = atan2(z + e² N sin(lat), ρ); contracts by about e² per step.
  double lat = std::atan2(p.z(), rho * (1.0 - e2));
  for (int i = 0; i < 20; ++i) {
    const double s = std::sin(lat);
    const double n = e.a / std::sqrt(1.0 - e2 * s * s);
    const double next = std::atan2(p.z() + e2 * n * s, rho);
    const bool done = std::abs(next - lat) < 1e-15;
    lat = next;
    if (done) break;
  }
  g.lat = lat;
  const double s = std::sin(lat), c = std::cos(lat);
  // Height along the normal; this form has no division by cos(lat), so it holds at the poles too.
  g.h = rho * c + p.z() * s - e.a * std::sqrt(1.0 - e2 * s * s);
  return g;
}

LocalEnu::LocalEnu(const Geodetic& origin, const Ellipsoid& e)
    : origin_(origin), ellipsoid_(e), origin_ecef_(geodetic_to_ecef(origin, e)) {
  const double sl = std::sin(origin.lat), cl = std::cos(origin.lat);
  const double so = std::sin(origin.lon), co = std::cos(origin.lon);
  enu_from_ecef_ << -so, co, 0.0,  //
      -sl * co, -sl * so, cl,      //
      cl * co, cl * so, sl;
}

}  // namespace fsd
