#pragma once
// Shared helpers of the vehicle dynamics tests: stepping loops and a circle fit, all independent of the model.
#include <Eigen/Dense>
#include <cmath>
#include <functional>
#include <vector>

#include "drivers/sim/vehicle/vehicle_model.hpp"

namespace fsd::sim::test {

inline constexpr double kDt = 1.0 / 200.0;  // the simulator's fixed step
inline constexpr double kG = 9.81;          // the tests' own gravity

// Steps `seconds` of simulated time with a fixed command; `each` (optional) sees the truth after every step.
inline void run_for(VehicleModel& car, const ActuatorCommand& cmd, double seconds,
                    const std::function<void(const VehicleTruth&)>& each = {}) {
  const int n = static_cast<int>(std::lround(seconds / kDt));
  for (int i = 0; i < n; ++i) {
    car.step(kDt, cmd);
    if (each) each(car.truth());
  }
}

inline ActuatorCommand drive(double target_speed, double steering = 0.0) {
  ActuatorCommand c;
  c.drive_enabled = true;
  c.target_speed = target_speed;
  c.steering = steering;
  return c;
}

struct Circle {
  Eigen::Vector2d centre;
  double radius = 0;
  double rms_residual = 0;
};

// Algebraic (Kåsa) least-squares circle through points: x² + y² + D x + E y + F = 0.
inline Circle fit_circle(const std::vector<Eigen::Vector2d>& pts) {
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const auto& p : pts) mean += p;
  mean /= static_cast<double>(pts.size());
  Eigen::MatrixXd A(pts.size(), 3);
  Eigen::VectorXd b(pts.size());
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const Eigen::Vector2d q = pts[i] - mean;
    A.row(static_cast<Eigen::Index>(i)) << q.x(), q.y(), 1.0;
    b(static_cast<Eigen::Index>(i)) = -q.squaredNorm();
  }
  const Eigen::Vector3d s = A.colPivHouseholderQr().solve(b);
  Circle c;
  c.centre = mean + Eigen::Vector2d(-s(0) / 2, -s(1) / 2);
  c.radius = std::sqrt(s(0) * s(0) / 4 + s(1) * s(1) / 4 - s(2));
  double sum = 0;
  for (const auto& p : pts) sum += std::pow((p - c.centre).norm() - c.radius, 2);
  c.rms_residual = std::sqrt(sum / static_cast<double>(pts.size()));
  return c;
}

// ∫ from 0 to v0 of g(v) dv by Simpson's rule (n even).
inline double simpson(const std::function<double(double)>& g, double a, double b, int n = 2000) {
  const double h = (b - a) / n;
  double s = g(a) + g(b);
  for (int i = 1; i < n; ++i) s += (i % 2 ? 4.0 : 2.0) * g(a + i * h);
  return s * h / 3.0;
}

// Root of f on [lo, hi] by bisection (f(lo) and f(hi) of opposite signs).
inline double bisect(const std::function<double(double)>& f, double lo, double hi) {
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    if ((f(mid) > 0) == (f(lo) > 0))
      lo = mid;
    else
      hi = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace fsd::sim::test
