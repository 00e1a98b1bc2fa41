#pragma once
// A path for the car to follow: points in the map frame with heading, curvature, arc length and a target speed.
// Planners produce it, the speed profile fills v, followers track it, and the lap-2 trajectory is one.
#include <cstddef>
#include <optional>
#include <vector>

#include "common/geometry.hpp"
#include "common/time.hpp"

namespace fsd {

struct PathPoint {
  Vec2 p = Vec2::Zero();  // map frame, m
  double yaw = 0;         // tangent heading, rad
  double kappa = 0;       // signed curvature, 1/m (left turn positive)
  double s = 0;           // arc length from the first point, m
  double v = 0;           // target speed, m/s
};

struct Path {
  Stamp stamp = 0;  // time of the data it was planned from
  std::vector<PathPoint> points;
  bool closed = false;  // the last point joins the first (a lap)

  bool empty() const { return points.size() < 2; }
  // Total arc length; for a closed path including the closing segment.
  double length() const;
};

// Where a point lies relative to a path.
struct PathProjection {
  double s = 0;              // arc length of the foot point
  double lateral = 0;        // signed offset of the point from the path, m (left of the path positive)
  std::size_t index = 0;     // segment start index: the foot lies between points[index] and the next one
  Vec2 foot = Vec2::Zero();  // closest point on the path
  double yaw = 0;            // path heading at the foot
  double kappa = 0;          // path curvature at the foot
  double v = 0;              // path speed at the foot
  double distance() const { return lateral < 0 ? -lateral : lateral; }
};

// Recomputes s, yaw and kappa from the positions (kappa by the circle through three neighbours).
void compute_geometry(Path& path);
// Moves every point by the rigid `by` (position and heading; s, kappa and speeds are unchanged by it).
void transform_path(Path& path, const Pose2& by);
// Points at uniform arc-length spacing `ds` along the positions (the last spacing of an open path may be
// shorter); speeds interpolated; geometry recomputed.
Path resample(const Path& path, double ds);
// Point at arc length s: clamped on an open path, wrapped on a closed one; every field interpolated.
PathPoint sample(const Path& path, double s);
// Wraps s into [0, length) on a closed path, clamps into [0, length] on an open one.
double normalize_s(const Path& path, double s);
// Signed arc-length difference b - a, the short way round on a closed path.
double s_difference(const Path& path, double a, double b);

// Closest point on the whole path. Returns nullopt for an empty path.
std::optional<PathProjection> project(const Path& path, const Vec2& point);
// Closest point among segments within [s_hint - back, s_hint + ahead]: keeps the projection on the right
// branch where a path comes close to itself (a skid pad's figure eight, the laps of a closed track).
std::optional<PathProjection> project(const Path& path, const Vec2& point, double s_hint, double back, double ahead);

}  // namespace fsd
