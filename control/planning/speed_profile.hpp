#pragma once
// Speed along a path under the car's limits: a forward–backward pass with the friction circle
// (√(ax² + ay²) ≤ μg, ay = v²κ), the motor's acceleration and power limits, the brake limit, v_max, and the
// steering's rate limit where the curvature changes fast (an S-bend: v·|dκ/ds| ≤ κ̇max).
// Open paths run from the car's current speed to an end speed; closed paths (laps) are periodic.
#include <vector>

#include "control/planning/path.hpp"

namespace fsd {

struct SpeedLimits {
  double mu = 0.9;           // friction coefficient the profile may use (already including any margin)
  double g = 9.81;           // m/s²
  double a_accel_max = 5.0;  // motor traction limit, m/s²
  double a_brake_max = 8.0;  // service brake limit, m/s²
  double power_max = 0.0;    // power at the wheels, W; 0 = no power limit
  double mass = 230.0;       // kg, with driver-less payload; used with power_max only
  double v_max = 20.0;       // m/s
  // Fastest change of path curvature the steering can make, 1/(m·s): the steering rate over the wheelbase
  // (δ ≈ L·κ, so δ̇ ≈ L·κ̇; exact at small angles, cautious at large ones). 0 = no limit.
  double kappa_rate_max = 0.0;
  double kappa_rate_window = 4.0;  // m: dκ/ds is taken over this much path (the steering starts early)
  // Traction on the friction ellipse a_x/a_accel_max, a_y/(μg) (a rear-driven car's rear tyres corner too);
  // false: the friction circle's remainder capped at a_accel_max.
  bool traction_ellipse = true;
  // Steering: a car that understeers needs δ = atan(L·κ) + K·v²·κ (K rad per m/s² of lateral acceleration); each
  // point is driven no faster than keeps δ within the lock less `steer_reserve` (left for the follower to correct
  // with). understeer = 0: no such limit.
  double understeer = 0.0;      // K, rad per m/s²
  double wheelbase = 1.53;      // m
  double max_steer = 0.5;       // rad
  double steer_reserve = 0.01;  // rad
  double v_min = 1.0;           // m/s: the floor of that limit (a curvature the lock itself barely reaches)
  double steer_window = 1.0;    // m either side: the limit of the sharpest curvature within it (a path's curvature
                                // wavers a little between nodes; the car's speed cannot follow such ripples)
  // Stopping (open paths that end in a stop): at every point the car stops `stop_margin` short of the end even when
  // its braking begins `stop_latency` later: v ≤ −a·t + √((a·t)² + 2·a·d), a the service brakes.
  double stop_latency = 0.3;  // s
  double stop_margin = 1.0;   // m
};

// The highest speed from which a car braking at `decel` after `latency` stops within `distance` (0 when ≤ 0).
double stopping_speed(double distance, double decel, double latency);

// A stretch of path [s_begin, s_end] driven at most v_max (on a closed path s_begin > s_end wraps over the start).
struct SpeedZone {
  double s_begin = 0, s_end = 0;  // m along the path
  double v_max = 0;               // m/s
};

class SpeedProfile {
 public:
  explicit SpeedProfile(SpeedLimits limits = {}) : limits_(limits) {}
  const SpeedLimits& limits() const { return limits_; }

  // Highest steady speed on curvature kappa: √(μg/|κ|), capped at v_max.
  double curvature_limit(double kappa) const;
  // Highest speed at which the understeering car holds curvature kappa with the steering's reserve left.
  double steering_limit(double kappa) const;
  // Highest speed at which the steering keeps up with a curvature changing by dkappa_ds (1/m²).
  double curvature_rate_limit(double dkappa_ds) const;
  // Largest acceleration (≥ 0) at speed v on curvature kappa: friction circle, traction and power.
  double max_acceleration(double v, double kappa) const;
  // Largest deceleration (≥ 0) at speed v on curvature kappa: friction circle and brakes.
  double max_deceleration(double v, double kappa) const;

  // Fills v of every point. Open path: starting from v_start, ending no faster than v_end; v_end = 0 is a stop,
  // kept with the stopping rule above.
  // Closed path: periodic, v_start and v_end ignored. `zones` cap stretches of the path on top of the limits.
  void apply(Path& path, double v_start, double v_end, const std::vector<SpeedZone>& zones = {}) const;
  // The same for an open path that is known free only up to `s_stop`: a stop there, zero beyond; the path's points
  // stay as they are (a follower on it keeps its place).
  void apply_until(Path& path, double v_start, double s_stop) const;

 private:
  SpeedLimits limits_;
};

// Time to drive the path at its speeds (each segment at the mean of its end speeds); +inf if it stops inside.
double travel_time(const Path& path);

}  // namespace fsd
