#include "control/missions/missions.hpp"

#include <algorithm>
#include <cmath>

namespace fsd {

SpeedLimits SpeedConfig::realtime() const {
  SpeedLimits l;
  l.mu = mu * mu_margin_realtime;
  l.a_accel_max = a_accel_max;
  l.a_brake_max = a_brake_max;
  l.power_max = power_max;
  l.mass = mass;
  l.v_max = std::min(v_max, v_max_realtime);
  l.kappa_rate_max = kappa_rate_max;
  l.traction_ellipse = traction_ellipse;
  l.understeer = understeer;
  l.steer_reserve = steer_reserve;
  l.wheelbase = wheelbase;
  l.max_steer = max_steer;
  l.stop_latency = stop_latency;
  l.stop_margin = stop_margin;
  return l;
}

SpeedLimits SpeedConfig::known() const {
  SpeedLimits l = realtime();
  l.mu = mu * mu_margin_known;
  l.v_max = v_max;
  return l;
}

double stop_speed(double v_finish, double travelled, double decel, double max_distance) {
  const double v0 = std::max(0.0, v_finish);
  // Aim at 80 % of the allowed distance: the speed loop lags the target.
  const double a = std::max({decel, v0 * v0 / (1.6 * std::max(max_distance, 1.0)), 0.1});
  const double d_stop = v0 * v0 / (2.0 * a);
  const double left = d_stop - std::max(0.0, travelled);
  return left > 0 ? std::sqrt(2.0 * a * left) : 0.0;
}

}  // namespace fsd
