#pragma once
// The one path optimizer (DESIGN.md §5c): a path through the corridor the cones leave that the car can drive, for
// lap 1's real-time plans (open, from the car) and lap 2's whole lap (closed), planned over its whole length at once
// so that consecutive turns are planned together.
//
// The path's nodes sit on the normals of a reference line (lap 1: the midline of the corridor walk; lap 2: the
// mapped centre line), each moved by an offset α within its bounds (the corridor, less half the body). The offsets
// minimise, per metre,  w_centre·α² + w_curvature·κ² + w_curvature_rate·(dκ/ds)²  (the centre line, a minimum-
// curvature line, or any blend: the κ² term grows fastest in tight turns, so those are cut most) subject to
//   - the body (car.*'s rectangle at each node and half-way between nodes, heading along the path) keeping
//     `clearance` from every cone's base, and costing below `clearance_soft`;
//   - |κ| ≤ the steering lock's curvature less `lock_margin` (costing beyond `lock_margin_soft`), and
//     |dκ/ds| ≤ kappa_rate_max (the steering's rate at the slowest speed a turn-in is driven; the speed profile
//     then keeps v·|dκ/ds| within the steering's rate).
// It is a nonlinear least-squares problem solved by Ceres (Levenberg–Marquardt); the inequality constraints are
// exact penalties (hinges weighted by `penalty`), so the solver's answer is only a candidate: the planners check the
// body along the result exactly (control/planning/footprint.hpp) and keep only the part that is clear.
#include <optional>
#include <vector>

#include "common/geometry.hpp"
#include "control/planning/footprint.hpp"

namespace fsd {

struct PathOptimizerConfig {
  double w_centre = 1.0;           // per m, on α² (m²)
  double w_curvature = 10.0;       // per m, on κ² (1/m²)
  double w_curvature_rate = 2.0;   // per m, on (dκ/ds)² (1/m⁴)
  double lock_margin = 0.005;      // share of the lock's curvature never planned (the lock itself, less a hair)
  double lock_margin_soft = 0.08;  // share below the lock where curvature starts to cost
  double w_lock_soft = 200.0;      // per m, on the excess² (1/m²)
  double kappa_rate_max = 1.5;     // 1/m²: steepest change of curvature along the path (the steering at 0.5 m/s)
  double clearance = 0.02;         // m asked between the body and every cone's base (the check accepts less)
  double clearance_soft = 0.3;     // m below which the clearance costs
  double w_clearance_soft = 20.0;  // per m, on the shortfall² (1/m²)
  double penalty = 1e7;            // weight of a hard constraint's violation² (the same units as its cost)
  int max_iterations = 60;
};

struct OptimizerInput {
  std::vector<Vec2> reference;          // nodes of the reference line, about evenly spaced
  std::vector<Vec2> normals;            // unit normals to its left, one per node
  std::vector<double> lo, hi;           // bounds of each node's offset α along its normal (lo ≤ 0 ≤ hi expected)
  bool closed = false;                  // a lap: the last node joins the first
  int fixed = 0;                        // open: the first nodes stay on the reference (node 0: the car's position)
  std::optional<double> start_heading;  // open: the path leaves node 0 this way (rad, the reference's frame)
  std::optional<double> start_kappa;    // open: with the curvature the car drives now,
  double start_kappa_slack = 0;         // ... give or take what its steering can change by the first node
  double free_from = 0;                 // m: no clearance asked before this far along (the car stands where it is)
  double rate_free_until = 0;  // m: no limit on dκ/ds before this far along (a car at standstill steers in place)
  std::vector<Obstacle> obstacles;
};

struct OptimizerOutput {
  std::vector<Vec2> points;  // the nodes moved by their offsets
  std::vector<double> alpha;
  bool converged = false;  // the solver stopped on a tolerance, not on its iteration cap
  int iterations = 0;
  double cost = 0;
};

class PathOptimizer {
 public:
  // `kappa_lock`: the curvature of the steering lock, tan(max_steer) / wheelbase.
  PathOptimizer(PathOptimizerConfig config, Body body, double kappa_lock);
  // Empty points for input of mismatched sizes or fewer than 4 nodes.
  OptimizerOutput solve(const OptimizerInput& in, const std::vector<double>* start_alpha = nullptr) const;

  const PathOptimizerConfig& config() const { return config_; }
  double kappa_max() const { return (1.0 - config_.lock_margin) * kappa_lock_; }

 private:
  PathOptimizerConfig config_;
  Body body_;
  double kappa_lock_;
};

}  // namespace fsd
