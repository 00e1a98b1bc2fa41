#pragma once
// What every planned path keeps (control.path.*): the optimizer's weights and margins, the cones' size, and the
// body they are kept from (car.*). Lap 1's real-time plans and lap 2's whole lap share it.
#include "control/planning/footprint.hpp"
#include "control/planning/path_optimizer.hpp"

namespace fsd {

struct PathConfig {
  PathOptimizerConfig optimizer;
  double node_spacing = 0.5;     // m between the optimizer's nodes (the path: them and an arc point between each two)
  double cone_radius = 0.12;     // m: a small cone's base (228 mm) and a little
  double big_cone_radius = 0.15; // m: a big orange cone's (285 mm)
  // The result is checked along its whole length; a stretch whose body comes nearer a cone than this is cut off
  // (lap 1) or refused (lap 2). Below the optimizer's clearance: it asks for more than it needs.
  double accept_clearance = 0.0;  // m
  // ... and one that curves more than the lock's curvature by this share (where it fights the clearance at the
  // steering's very reach, the optimizer's answer can pass the lock by a hair; more than this is no path).
  double accept_lock_excess = 0.02;
  // Not configuration keys: the car (car.*).
  Body body;
  double wheelbase = 1.53;
  double max_steer = 0.5;
  double kappa_lock() const;
  // First arc length of `path` where |κ| passes the lock by more than accept_lock_excess; +inf when nowhere.
  double first_beyond_lock(const Path& path) const;
};

}  // namespace fsd
