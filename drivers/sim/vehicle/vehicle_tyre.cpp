#include "drivers/sim/vehicle/vehicle_tyre.hpp"

#include <cmath>

namespace fsd::sim {

double lateral_force(const MagicFormula& mf, double alpha, double peak) {
  const double ba = mf.b * alpha;
  return peak * std::sin(mf.c * std::atan(ba - mf.e * (ba - std::atan(ba))));
}

double slip_angle(double u, double w) { return -std::atan2(w, std::abs(u)); }

double friction_circle_scale(double fx_demand, double fy_tyre, double limit) {
  const double total = std::hypot(fx_demand, fy_tyre);
  return total <= limit ? 1.0 : limit / total;
}

}  // namespace fsd::sim
