// Acceleration and skid pad layouts: the rules fix their shape; the seed picks what the rules leave open
// (lane width, cone spacing, braking-zone length, staging, exit length) and the layout's heading.
#include <cmath>
#include <numbers>

#include "drivers/sim/track_generator/track_generator_detail.hpp"

namespace fsd::sim::detail {

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kAccelLength = 75.0;  // m, start line to finish line
constexpr double kRowGap = 1.2;        // m between the cones of a closing row (the car is 1.4 m wide)

// The skid pad (rules): circle centres 18.25 m apart, inner diameter 15.25 m, outer 21.25 m (a 3 m lane),
// 16 cones on each inner and 13 on each outer circle; the timing line through both centres.
constexpr double kSkidCentre = 9.125, kSkidInner = 7.625, kSkidOuter = 10.625;
constexpr int kSkidInnerCones = 16, kSkidOuterCones = 13;
constexpr double kSkidEntry = 15.0;  // m from car_start to the timing line (the shared EPFL files)
constexpr double kSkidLane = 1.5;    // m: half the entry and exit lane

// Maps layout coordinates (x along the start heading from car_start, y to its left) to the map.
struct Frame {
  Pose2 pose;
  Vec2 operator()(double x, double y) const { return pose.transform(Vec2(x, y)); }
};

// Cones on y from x0 (exclusive) to x1 (inclusive), evenly at most `spacing` apart.
void row_along(Track& t, ConeRole role, const Frame& f, double y, double x0, double x1, double spacing) {
  const int n = std::max(1, static_cast<int>(std::ceil((x1 - x0) / spacing - 1e-9)));
  for (int k = 1; k <= n; ++k) add_cone(t, role, f(x0 + (x1 - x0) * k / n, y));
}

}  // namespace

Track generate_acceleration(const TrackGeneratorOptions& o) {
  Rng rng(hash64(o.seed, 0x200));
  const double w = sample_range(rng, o.width_min, o.width_max, 0.4, o.width_min);
  const double spacing = sample_range(rng, o.spacing_min, o.spacing_max, 0.5, o.spacing_max);
  const double braking = sample_range(rng, o.braking_min, o.braking_max, 0.2, o.braking_max);
  const double staging = rng.uniform(2.0, 6.0);  // m from car_start to the start line (AMZ 2 m, EPFL 5.1 m)
  const double yaw = rng.uniform(-kPi, kPi);
  Track t;
  t.start = {0.0, 0.0, yaw};
  const Frame f{t.start};
  const double start = staging, finish = staging + kAccelLength, end = finish + braking;
  for (double y : {0.5 * w, -0.5 * w}) {
    const ConeRole side = y > 0 ? ConeRole::Left : ConeRole::Right;
    for (double x : {start, finish}) {
      add_cone(t, ConeRole::Timing, f(x - kTimingHalfGap, y));
      add_cone(t, ConeRole::Timing, f(x + kTimingHalfGap, y));
    }
    // Boundary cones between the timing lines; the braking zone's sides are orange.
    row_along(t, side, f, y, start + kTimingHalfGap, finish - kTimingHalfGap, spacing);
    t.cones.pop_back();  // the last one would stand on the finish line's first big orange cone
    row_along(t, ConeRole::Other, f, y, finish + kTimingHalfGap, end, spacing);
  }
  // The row across the end of the braking zone, between its two corner cones.
  const int gaps = static_cast<int>(std::ceil(w / kRowGap - 1e-9));
  for (int k = 1; k < gaps; ++k) add_cone(t, ConeRole::Other, f(end, -0.5 * w + w * k / gaps));
  return t;
}

Track generate_skidpad(const TrackGeneratorOptions& o) {
  Rng rng(hash64(o.seed, 0x300));
  const double exit = rng.uniform(20.0, 25.0);  // m of exit lane past the timing line (EPFL 20 m, AMZ 21 m)
  const double yaw = rng.uniform(-kPi, kPi);
  Track t;
  t.start = {0.0, 0.0, yaw};
  // Layout coordinates with the crossing at x = kSkidEntry.
  const Frame f{t.start};
  auto at = [&](double x, double y) { return f(x + kSkidEntry, y); };
  // Each circle in the colours of the DV track marking as it is driven: clockwise round the right circle its
  // inner ring is on the car's right (yellow), the outer on its left (blue); the left circle the other way.
  for (int side : {-1, 1}) {
    const Vec2 centre(0.0, side * kSkidCentre);
    const double towards_crossing = side < 0 ? 0.5 * kPi : -0.5 * kPi;
    const ConeRole inner = side < 0 ? ConeRole::Right : ConeRole::Left;
    const ConeRole outer = side < 0 ? ConeRole::Left : ConeRole::Right;
    for (int k = 0; k < kSkidInnerCones; ++k) {
      const double a = towards_crossing + 2.0 * kPi * k / kSkidInnerCones;
      add_cone(t, inner, at(centre.x() + kSkidInner * std::cos(a), centre.y() + kSkidInner * std::sin(a)));
    }
    // The outer ring leaves a quarter open round the crossing, where the other circle's inner ring is the edge.
    for (int k = 0; k < kSkidOuterCones; ++k) {
      const double a = towards_crossing + 0.25 * kPi + 1.5 * kPi * k / (kSkidOuterCones - 1);
      add_cone(t, outer, at(centre.x() + kSkidOuter * std::cos(a), centre.y() + kSkidOuter * std::sin(a)));
    }
  }
  // The timing line through the centres: two big orange cones each side of the lane.
  for (double x : {-0.75, 0.75})
    for (double y : {-1.55, 1.55}) add_cone(t, ConeRole::Timing, at(x, y));
  // Entry lane (the car stands in it) and exit lane in small orange cones; a row closes the exit.
  for (double x : {-12.5, -9.5})
    for (double y : {-kSkidLane, kSkidLane}) add_cone(t, ConeRole::Other, at(x, y));
  for (double y : {-kSkidLane, kSkidLane}) {
    add_cone(t, ConeRole::Other, at(9.5, y));
    row_along(t, ConeRole::Other, {Pose2{at(0, 0).x(), at(0, 0).y(), yaw}}, y, 9.5, exit, 2.5);
  }
  for (double y : {-0.5, 0.5}) add_cone(t, ConeRole::Other, at(exit, y));
  return t;
}

}  // namespace fsd::sim::detail
