// The whole-lap circle of public layouts (`circle`): one constant turn at the rules' minimum, a 3 m lane between
// an inner ring of radius 1.5 m and an outer one of 4.5 m (the 9 m outside diameter), with the car starting
// inside it as a crew would place it: its body's middle on the centre circle (radius 3 m), heading along it. About 16 cones and no timing cones, as the
// public layout has. The seed picks the heading, the direction and the cones on each ring; the hand-placement
// options apply as on a loop (docs/track-generator.md).
#include <algorithm>
#include <cmath>
#include <numbers>

#include "drivers/sim/track_generator/track_generator_detail.hpp"

namespace fsd::sim::detail {

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kInner = kHairpinOuterMin - kLaneMin;         // m: 1.5
constexpr double kCentre = kHairpinOuterMin - 0.5 * kLaneMin;  // m: 3, where the car starts
constexpr double kGapMax = 5.0;                                // m: the rules' largest gap along a boundary
constexpr int kInnerMin = 5, kInnerMax = 8, kOuterMin = 8, kOuterMax = 12;
// A car at the start: 2.5 m ahead of and 0.5 m behind car_start (its rear axle), 0.75 m either side; kept 0.3 m clear.
constexpr double kCarFront = 2.5, kCarRear = 0.5, kCarHalf = 0.75, kCarClear = 0.3;

// Cones on a ring of `radius`, at least as many as keep every gap within the rules' 5 m once uneven (1 + S) and
// moved (twice the jitter).
int ring_count(Rng& rng, const TrackGeneratorOptions& o, double radius, int lo, int hi) {
  const double even_max = (kGapMax - 2.0 * o.cone_jitter) / (1.0 + o.spacing_jitter);
  lo = std::max(lo, static_cast<int>(std::ceil(2.0 * kPi * radius / even_max - 1e-9)));
  return rng.uniform_int(lo, std::max(lo, hi));
}

}  // namespace

Track generate_circle(const TrackGeneratorOptions& o) {
  Rng rng(hash64(o.seed, 0x600 + static_cast<std::uint64_t>(o.kind)));
  const double yaw = rng.uniform(-kPi, kPi);
  const int dir = rng.chance(0.5) ? 1 : -1;  // +1 counter-clockwise: the inner ring on the car's left
  const int inner_n = ring_count(rng, o, kInner, kInnerMin, kInnerMax);
  const int outer_n = ring_count(rng, o, kHairpinOuterMin, kOuterMin, kOuterMax);
  Rng hand(hash64(o.seed, 0x601 + static_cast<std::uint64_t>(o.kind)));

  // car_start is the rear axle; the body's middle stands on the centre circle. With the rear axle there instead, the
  // nose's outer corner would stand at 4.41 m about the centre, beyond the outer cones' inner edge (4.38 m), and no
  // steering could bring the body round: even at the lock it sweeps out to 4.44 m from there.
  const Vec2 start(0.0, 0.0);
  const Vec2 heading(std::cos(yaw), std::sin(yaw));
  const Vec2 middle = start + 0.5 * (kCarFront - kCarRear) * heading;
  const Vec2 centre = middle + dir * kCentre * Vec2(-heading.y(), heading.x());
  const double a0 = yaw - dir * 0.5 * kPi;  // the body's middle's angle about the centre
  struct RingCone {
    Vec2 p;
    double angle;
  };
  // Each ring in driving order from the car; uneven gaps move each cone by up to S/2 of a gap along the ring.
  auto ring = [&](double radius, int count, double phase) {
    std::vector<RingCone> cones;
    for (int k = 0; k < count; ++k) {
      const double shift = o.spacing_jitter > 0.0 ? o.spacing_jitter * (hand.uniform() - 0.5) : 0.0;
      const double a = a0 + dir * 2.0 * kPi * (k + phase + shift) / count;
      cones.push_back({centre + radius * Vec2(std::cos(a), std::sin(a)), a});
    }
    return cones;
  };
  // The car must stand clear of every cone at the start: its nose's corner on the outside runs on 4.41 m about the
  // centre, so an outer cone 33° ahead of it would stand where the car does. The rings' phases (each the first
  // cone's place, in gaps) are drawn again until no cone is within the box of a car (3 × 1.5 m) and 0.3 m round it.
  const Pose2 car{start.x(), start.y(), yaw};
  auto in_the_car = [&](const std::vector<RingCone>& cones) {
    return std::any_of(cones.begin(), cones.end(), [&](const RingCone& c) {
      const Vec2 l = car.inverse_transform(c.p);
      return l.x() > -kCarRear - kCarClear && l.x() < kCarFront + kCarClear && std::abs(l.y()) < kCarHalf + kCarClear;
    });
  };
  std::vector<RingCone> inner, outer;
  for (int attempt = 0; attempt < 100; ++attempt) {
    const double inner_phase = rng.uniform(), outer_phase = rng.uniform();
    inner = ring(kInner, inner_n, inner_phase);
    outer = ring(kHairpinOuterMin, outer_n, outer_phase);
    if (!in_the_car(inner) && !in_the_car(outer)) break;
  }
  // One inner cone out of its ring into the lane; that ring then stays exactly in place.
  const bool outlier = o.inner_outlier > 0.0;
  if (outlier) {
    RingCone& c = inner[static_cast<std::size_t>(hand.uniform_int(0, inner_n - 1))];
    c.p += o.inner_outlier * (c.p - centre).normalized();
  }
  // Jitter only away from the lane: it is at the rules' 3 m, and the outside at the rules' 4.5 m radius.
  auto jitter = [&](std::vector<RingCone>& cones, double outward_sign) {
    for (RingCone& c : cones) {
      const Vec2 radial(std::cos(c.angle), std::sin(c.angle));
      const Vec2 along = dir * Vec2(-radial.y(), radial.x());
      const Vec2 d = hand_offset(hand, o.cone_jitter, 0.0);
      c.p += d.x() * along + d.y() * outward_sign * radial;
    }
  };
  if (o.cone_jitter > 0.0) {
    if (!outlier) jitter(inner, -1.0);
    jitter(outer, 1.0);
  }
  Track t;
  t.start = {start.x(), start.y(), yaw};
  const auto& left = dir > 0 ? inner : outer;
  const auto& right = dir > 0 ? outer : inner;
  for (const RingCone& c : left) add_cone(t, ConeRole::Left, c.p);
  for (const RingCone& c : right) add_cone(t, ConeRole::Right, c.p);
  return t;
}

}  // namespace fsd::sim::detail
