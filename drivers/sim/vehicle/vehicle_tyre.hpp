#pragma once
// Tyre forces of one axle of the single-track model: the Pacejka magic formula for the lateral force and a
// friction circle that couples it with the longitudinal (drive or brake) force.

namespace fsd::sim {

struct MagicFormula {
  double b = 10.0;  // stiffness factor, 1/rad
  double c = 1.5;   // shape factor
  double e = 0.0;   // curvature factor
};

// Lateral force of an axle at slip angle `alpha` (rad, positive when the wheel points left of its velocity,
// which gives a force to the left) with peak force `peak` = μ·Fz.
double lateral_force(const MagicFormula& mf, double alpha, double peak);

// Slip angle of a wheel whose contact patch moves at (u, w) in the wheel frame (u forward, w left): the angle
// from its velocity to its heading, measured against the rolling direction so that a wheel sliding backwards
// still gets a force opposing its sideways motion.
double slip_angle(double u, double w);

// Friction circle: when the demanded longitudinal force and the tyre's lateral force together exceed `limit`
// (μ·Fz), both are scaled down by the same factor onto the circle; returns that factor in (0, 1]. Models a tyre
// at its friction limit with traction control and ABS: the force saturates instead of the wheel spinning up or
// locking.
double friction_circle_scale(double fx_demand, double fy_tyre, double limit);

}  // namespace fsd::sim
