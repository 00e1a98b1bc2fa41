#pragma once
// The car's body on the ground (the rectangle of car.*: nose ahead of the rear axle, tail behind it, half its width
// either side) and how far it stands from a cone. Planning keeps it clear of every cone along a path; tracking
// checks it along the car's predicted motion. One definition, used by both and by the tests' hand-made cases.
//
// body_clearance() is a template so that the path optimizer can differentiate it (ceres::Jet); with doubles it is
// the exact signed distance from a disc (a cone's base) to the rectangle: > 0 apart, < 0 overlapping.
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "common/geometry.hpp"
#include "common/types.hpp"
#include "control/planning/path.hpp"

namespace fsd {

struct Body {
  double front = 2.4;       // m, rear axle to nose
  double rear = 0.5;        // m, rear axle to tail
  double half_width = 0.7;  // m
  // Farthest point of the body from the rear axle.
  double reach() const { return std::hypot(std::max(front, rear), half_width); }
};

// A cone's base as the body must avoid it: its centre on the ground and its radius.
struct Obstacle {
  Vec2 p = Vec2::Zero();
  double radius = 0.12;
};

// Obstacles from mapped cones: big orange cones are wider (285 mm base) than the others (228 mm).
std::vector<Obstacle> obstacles_of(const std::vector<Cone>& cones, double cone_radius, double big_cone_radius);

// Signed distance from the disc (cx, cy, radius) to the body of a car whose rear axle stands at (x, y) heading yaw.
template <typename T>
T body_clearance(const T& x, const T& y, const T& yaw, double cx, double cy, double radius, const Body& b) {
  using std::abs;
  using std::cos;
  using std::sin;
  using std::sqrt;
  const T dx = cx - x, dy = cy - y;
  const T c = cos(yaw), s = sin(yaw);
  const T along = c * dx + s * dy;    // the cone in the body frame: ahead of the rear axle
  const T across = -s * dx + c * dy;  // and to its left
  const T side = abs(across);
  const T zero(0.0);
  const T out_x = along > T(b.front) ? along - b.front : (along < T(-b.rear) ? T(-b.rear) - along : zero);
  const T out_y = side > T(b.half_width) ? side - b.half_width : zero;
  T d;
  if (out_x > zero && out_y > zero) {
    d = sqrt(out_x * out_x + out_y * out_y);
  } else if (out_x > zero) {
    d = out_x;
  } else if (out_y > zero) {
    d = out_y;
  } else {  // the centre inside the rectangle: minus the depth to its nearest side
    const T to_front = T(b.front) - along, to_rear = along + b.rear, to_side = T(b.half_width) - side;
    d = -(to_front < to_rear ? (to_front < to_side ? to_front : to_side) : (to_rear < to_side ? to_rear : to_side));
  }
  return d - radius;
}

inline double body_clearance(const Pose2& pose, const Obstacle& o, const Body& b) {
  return body_clearance(pose.x, pose.y, pose.yaw, o.p.x(), o.p.y(), o.radius, b);
}

// The body at every `step` metres of `path` from s_from to s_to (clamped to the path; a closed path wraps), heading
// along the path there.
struct SweepResult {
  double min_clearance = std::numeric_limits<double>::infinity();  // m, over the stretch
  double min_s = 0;                                                 // where (arc length)
  // First arc length where the clearance falls below the margin asked; +inf when it never does.
  double first_short_s = std::numeric_limits<double>::infinity();
  int first_short_obstacle = -1;  // which obstacle, index into the list given
};
SweepResult sweep_body(const Path& path, const std::vector<Obstacle>& obstacles, const Body& body, double margin,
                       double step = 0.05, double s_from = 0, double s_to = std::numeric_limits<double>::infinity());

// The body along a sequence of poses (a predicted motion): the first pose closer than `margin` to an obstacle.
struct PoseSweepResult {
  int first_short = -1;  // index of the first pose short of the margin; −1: none
  int obstacle = -1;
  double clearance = std::numeric_limits<double>::infinity();  // of that pose (or the least over all when none)
};
PoseSweepResult sweep_poses(const std::vector<Pose2>& poses, const std::vector<Obstacle>& obstacles, const Body& body,
                            double margin);

}  // namespace fsd
