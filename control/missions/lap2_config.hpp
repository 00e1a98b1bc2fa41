#pragma once
// Lap 2 and later laps on the recorded trajectory (PathSource::Recorded) get their own friction share and
// follower gains: the path is known and smooth, so it can be tracked tighter and driven nearer the grip limit
// than what lap 1, acceleration and skid pad see (their tuning stays in control.follower / control.speed).
#include "control/tracking/follower.hpp"

namespace fsd {

struct Lap2Config {
  double mu_margin = 1.0;      // share of mu of the lap-2 speed profile (tracked exactly: see speed_lead_brake)
  double lqr_q_lateral = 1.0;  // 1/m²
  double lqr_q_heading = 1.0;  // 1/rad²
  double lqr_r = 2.0;          // 1/rad²
  double speed_preview = 0.4;  // s: target speed taken this far ahead on the lap path
  double speed_lead = 0.2;     // s: plus the path's acceleration times this (≈ 1 / the VCU speed-loop gain)
  // s: the same where the path slows down. With the preview, 0.5 s: the VCU speed loop's time constant (1/kp), by
  // which a proportional loop lags a ramp, so the car brakes where the profile does and meets each corner at its
  // planned speed instead of up to 1 m/s above it.
  double speed_lead_brake = 0.1;

  // The lap-1 follower settings with the lap-2 gains on top.
  FollowerConfig follower(const FollowerConfig& base) const {
    FollowerConfig c = base;
    c.lqr_q_lateral = lqr_q_lateral;
    c.lqr_q_heading = lqr_q_heading;
    c.lqr_r = lqr_r;
    c.speed_preview = speed_preview;
    c.speed_lead = speed_lead;
    c.speed_lead_brake = speed_lead_brake;
    return c;
  }
};

}  // namespace fsd
