#include "drivers/sim/vehicle_tyre.hpp"

#include <cmath>

namespace fsd::sim {

double lateral_force(const MagicFormula& mf, double alpha, double peak) {
  const double ba = mf.b * alpha;
  return peak * std::sin(mf.c * std::atan(ba - mf.e * (ba - std::atan(ba))));
}

AxleForce friction_circle(double fx_demand, double fy_tyre, double limit) {
  const double total = std::hypot(fx_demand, fy_tyre);
  if (total <= limit || total <= 0.0) return {fx_demand, fy_tyre};
  const double k = limit / total;
  return {fx_demand * k, fy_tyre * k};
}

}  // namespace fsd::sim
