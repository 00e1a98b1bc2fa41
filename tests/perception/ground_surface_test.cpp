// The local ground corrections (ground_surface.hpp) on hand-made VLP-16 returns: a sensor 0.35 m above flat ground,
// its lasers' rings of ground returns one per 0.2° of azimuth, and what stands on the ground. The truth is the
// geometry the points are made from.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "perception/ground_surface.hpp"

namespace fsd {
namespace {

constexpr double kMount = 0.35;                                   // m above the ground
constexpr double kStep = 0.2 * std::numbers::pi / 180.0;          // azimuth step, rad
constexpr double kLaser[] = {-15, -13, -11, -9, -7, -5, -3, -1};  // the VLP-16's downward lasers, degrees

Point at(double x, double y, double z) {
  Point p;
  p.x = static_cast<float>(x), p.y = static_cast<float>(y), p.z = static_cast<float>(z);
  return p;
}

// Each downward laser's ring over ±40° of azimuth, on a ground at z = −kMount + rise(range).
template <class Rise>
std::vector<Point> ground_rings(Rise rise) {
  std::vector<Point> pts;
  for (double deg : kLaser) {
    const double down = std::tan(-deg * std::numbers::pi / 180.0);
    // Where the laser meets the ground: range·down = kMount − rise(range), solved by a few fixed-point steps.
    double r = kMount / down;
    for (int k = 0; k < 20; ++k) r = (kMount - rise(r)) / down;
    for (double a = -0.7; a <= 0.7; a += kStep) pts.push_back(at(r * std::cos(a), r * std::sin(a), -kMount + rise(r)));
  }
  return pts;
}

LocalGroundConfig config(bool density) {
  LocalGroundConfig cfg;
  cfg.azimuth_step = density ? kStep : 0.0;
  return cfg;
}

TEST(GroundSurface, ARowOfConesOneLaserCrossesIsNotTheGround) {
  // Flat ground; a boundary of small cones 10–14 m ahead, 2.5 m apart, where no laser reaches the ground (the −3°
  // laser lands at 6.7 m, the −1° at 20 m): the −1° laser crosses each at the same height through its stripe.
  std::vector<Point> pts = ground_rings([](double) { return 0.0; });
  const double stripe_z = -12.0 * std::tan(std::numbers::pi / 180.0);  // ≈ −0.21, 0.14 m above the ground
  for (double x = 10.0; x <= 14.0; x += 2.5)
    for (double y = 1.3; y <= 1.3 + 0.2; y += x * kStep) pts.push_back(at(x, y, stripe_z));  // 0.2 m of cone
  GroundPlane plane;
  plane.h = -kMount, plane.valid = true;

  GroundSurface with_density(plane);
  with_density.fit_local(pts, config(true));
  EXPECT_NEAR(with_density.offset_at(12.0, 1.4), 0.0, 0.01);
  EXPECT_NEAR(with_density.height_of(12.0, 1.4, stripe_z), stripe_z + kMount, 0.01);

  // Without the density test the cones' returns were taken for a ground layer at their height.
  GroundSurface without(plane);
  without.fit_local(pts, config(false));
  EXPECT_GT(without.offset_at(12.0, 1.4), 0.07);
}

TEST(GroundSurface, AGroundThatRisesFarOutIsStillFollowed) {
  // The ground rises 0.1 m from 12 m out (a crest): the −1° laser's ring lands on it at ~14 m, and the plane
  // (fitted near the car) is 0.1 m low there. The ring is dense, so the cells it crosses are corrected.
  const auto rise = [](double r) { return r >= 12.0 ? 0.1 : 0.0; };
  const std::vector<Point> pts = ground_rings(rise);
  GroundPlane plane;
  plane.h = -kMount, plane.valid = true;
  GroundSurface ground(plane);
  ground.fit_local(pts, config(true));
  const double r = (kMount - 0.1) / std::tan(std::numbers::pi / 180.0);  // where the −1° laser lands
  EXPECT_NEAR(ground.offset_at(r, 0.0), 0.1, 0.01);
  EXPECT_NEAR(ground.offset_at(4.0, 0.0), 0.0, 0.01);  // the flat ground near the car
}

}  // namespace
}  // namespace fsd
