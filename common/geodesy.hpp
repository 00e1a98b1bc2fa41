#pragma once
// Geodesy on an ellipsoid (WGS-84 by default): geodetic ↔ Earth-centred Earth-fixed (ECEF) ↔ local East-North-Up.
// Shared by the GNSS driver (geodetic → ENU) and the virtual car's GNSS model (ENU → geodetic), so that one is
// the exact inverse of the other. Angles in radians, heights above the ellipsoid in metres.
#include <Eigen/Core>

#include "common/geometry.hpp"

namespace fsd {

struct Ellipsoid {
  double a = 6378137.0;            // semi-major axis, m
  double f = 1.0 / 298.257223563;  // flattening

  static constexpr Ellipsoid wgs84() { return {6378137.0, 1.0 / 298.257223563}; }
  static constexpr Ellipsoid grs80() { return {6378137.0, 1.0 / 298.257222101}; }  // NAD 83, ETRS89
  constexpr double e2() const { return f * (2.0 - f); }                            // first eccentricity squared
  constexpr double b() const { return a * (1.0 - f); }                             // semi-minor axis, m
};

struct Geodetic {
  double lat = 0.0;  // rad, north positive
  double lon = 0.0;  // rad, east positive
  double h = 0.0;    // m above the ellipsoid (not above mean sea level)

  static Geodetic from_degrees(double lat_deg, double lon_deg, double h_m) {
    return {deg2rad(lat_deg), deg2rad(lon_deg), h_m};
  }
};

Vec3 geodetic_to_ecef(const Geodetic& g, const Ellipsoid& e = Ellipsoid::wgs84());
// Iterates the latitude to convergence (|Δlat| < 1e-15 rad, a few iterations near the Earth's surface); stable at
// the poles and the equator.
Geodetic ecef_to_geodetic(const Vec3& ecef, const Ellipsoid& e = Ellipsoid::wgs84());

// The local tangent frame at an origin: x east, y north, z up (normal to the ellipsoid at the origin).
class LocalEnu {
 public:
  explicit LocalEnu(const Geodetic& origin, const Ellipsoid& e = Ellipsoid::wgs84());

  Vec3 to_enu(const Geodetic& g) const { return ecef_to_enu(geodetic_to_ecef(g, ellipsoid_)); }
  Geodetic to_geodetic(const Vec3& enu) const { return ecef_to_geodetic(enu_to_ecef(enu), ellipsoid_); }
  Vec3 ecef_to_enu(const Vec3& ecef) const { return enu_from_ecef_ * (ecef - origin_ecef_); }
  Vec3 enu_to_ecef(const Vec3& enu) const { return origin_ecef_ + enu_from_ecef_.transpose() * enu; }

  const Geodetic& origin() const { return origin_; }
  const Ellipsoid& ellipsoid() const { return ellipsoid_; }

 private:
  Geodetic origin_;
  Ellipsoid ellipsoid_;
  Vec3 origin_ecef_;
  Eigen::Matrix3d enu_from_ecef_;  // rows: east, north, up unit vectors in ECEF
};

}  // namespace fsd
