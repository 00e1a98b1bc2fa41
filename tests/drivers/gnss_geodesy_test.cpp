// Geodesy (common/geodesy) against independent references:
//  - NGS datasheet of CORS P055 (Glendive, MT), NAD 83(2011) on the GRS80 ellipsoid: latitude, longitude and
//    ellipsoidal height with the published ECEF X/Y/Z (rounded to 1 mm);
//  - local ENU values computed with PROJ 9.1.1 (a separate implementation):
//      +proj=pipeline +step +proj=cart +ellps=WGS84
//                     +step +proj=topocentric +ellps=WGS84 +lat_0=49.3278 +lon_0=8.5658 +h_0=150
#include <gtest/gtest.h>

#include <cmath>

#include "common/geodesy.hpp"

namespace fsd {
namespace {

constexpr double kMm = 1e-3;

double dms(double d, double m, double s) { return d + m / 60.0 + s / 3600.0; }

TEST(Geodesy, NgsDatasheetEcef) {
  const Geodetic p055 = Geodetic::from_degrees(dms(47, 7, 0.14491), -dms(104, 41, 6.39476), 668.450);
  const Vec3 x = geodetic_to_ecef(p055, Ellipsoid::grs80());
  EXPECT_NEAR(x.x(), -1102409.924, kMm);
  EXPECT_NEAR(x.y(), -4206590.343, kMm);
  EXPECT_NEAR(x.z(), 4651093.534, kMm);

  const Geodetic back = ecef_to_geodetic(Vec3(-1102409.924, -4206590.343, 4651093.534), Ellipsoid::grs80());
  // 1e-5 arc seconds of the datasheet is 0.3 mm on the ground; its XYZ are rounded to 1 mm.
  EXPECT_NEAR(rad2deg(back.lat), dms(47, 7, 0.14491), 1.5e-8);
  EXPECT_NEAR(rad2deg(back.lon), -dms(104, 41, 6.39476), 1.5e-8);
  EXPECT_NEAR(back.h, 668.450, kMm);
}

TEST(Geodesy, EquatorAndPoleByDefinition) {
  const Ellipsoid e = Ellipsoid::wgs84();
  const Vec3 eq = geodetic_to_ecef(Geodetic::from_degrees(0, 90, 10), e);
  EXPECT_NEAR(eq.x(), 0.0, 1e-9);
  EXPECT_NEAR(eq.y(), e.a + 10, 1e-9);
  EXPECT_NEAR(eq.z(), 0.0, 1e-9);
  const Vec3 pole = geodetic_to_ecef(Geodetic::from_degrees(-90, 0, 0), e);
  EXPECT_NEAR(pole.z(), -6356752.314245, kMm);  // WGS-84 semi-minor axis
  const Geodetic g = ecef_to_geodetic(Vec3(0, 0, 6356752.314245 + 25.0), e);
  EXPECT_NEAR(rad2deg(g.lat), 90.0, 1e-12);
  EXPECT_NEAR(g.h, 25.0, kMm);
}

struct ProjCase {
  double lat, lon, h, e, n, u;
};

TEST(Geodesy, EnuMatchesProj) {
  const LocalEnu enu(Geodetic::from_degrees(49.3278, 8.5658, 150.0));
  const ProjCase cases[] = {
      {49.3278, 8.5658, 150.0, 0.0, 0.0, 0.0},
      {49.3368, 8.5658, 150.0, 0.0, 1000.969098, -0.078616},          // 1 km north
      {49.3278, 8.5795, 150.0, 995.881883, 0.090303, -0.077597},      // 1 km east
      {49.3278, 8.5658, 250.0, 0.0, 0.0, 100.0},                      // 100 m above the origin
      {49.33419, 8.57561, 250.0, 713.028448, 710.745349, 99.920587},  // 1 km north-east, 100 m up
      {49.3250, 8.5600, 140.0, -421.637480, -311.395615, -10.021518},
  };
  for (const auto& c : cases) {
    const Vec3 p = enu.to_enu(Geodetic::from_degrees(c.lat, c.lon, c.h));
    EXPECT_NEAR(p.x(), c.e, kMm) << c.lat << " " << c.lon;
    EXPECT_NEAR(p.y(), c.n, kMm) << c.lat << " " << c.lon;
    EXPECT_NEAR(p.z(), c.u, kMm) << c.lat << " " << c.lon;
  }
}

TEST(Geodesy, EnuRoundTrip) {
  for (const auto& origin : {Geodetic::from_degrees(49.3278, 8.5658, 150.0), Geodetic::from_degrees(-33.9, 151.2, 5),
                             Geodetic::from_degrees(0.0, -179.99, 0), Geodetic::from_degrees(89.999, 45, 3000)}) {
    const LocalEnu enu(origin);
    for (const Vec3& p : {Vec3(0, 0, 0), Vec3(1000, 0, 0), Vec3(0, -1000, 100), Vec3(3456.7, -2345.6, -45.6),
                          Vec3(-5000, 5000, 200), Vec3(0.02, -0.01, 0.03)}) {
      const Geodetic g = enu.to_geodetic(p);
      const Vec3 q = enu.to_enu(g);
      EXPECT_LT((q - p).norm(), 1e-6) << p.transpose();
    }
  }
}

TEST(Geodesy, GeodeticRoundTrip) {
  for (double lat : {-90.0, -60.0, -1e-9, 0.0, 30.0, 49.3278, 89.9999999}) {
    for (double h : {-100.0, 0.0, 150.0, 10000.0}) {
      const Geodetic g = Geodetic::from_degrees(lat, 8.5658, h);
      const Geodetic back = ecef_to_geodetic(geodetic_to_ecef(g));
      EXPECT_NEAR(back.lat, g.lat, 1e-12) << lat << " " << h;
      EXPECT_NEAR(back.h, g.h, 1e-6) << lat << " " << h;
      if (std::abs(lat) < 90) {
        EXPECT_NEAR(back.lon, g.lon, 1e-12);
      }
    }
  }
}

}  // namespace
}  // namespace fsd
