#pragma once
// Mission-level settings and the pieces of the missions that are plain geometry: the car's limits for the
// speed profiles and the braking to a stop after the finish.
#include <optional>
#include <string>
#include <vector>

#include "common/track.hpp"
#include "common/types.hpp"
#include "control/planning/path.hpp"
#include "control/planning/speed_profile.hpp"

namespace fsd {

// The car's limits and how much of them each kind of path may use.
struct SpeedConfig {
  double mu = 1.2;                  // tyre–road friction of the car (estimate, or the virtual car's)
  double mu_margin_realtime = 0.6;  // share of μ when planning on what is seen (lap 1, fallback, autocross)
  double mu_margin_known = 0.92;    // share of μ on a known straight (acceleration, EBS test); lap 2: control.lap2
  double mu_margin_skidpad = 0.92;  // share of μ on the skid pad (its curvature flips at the crossing)
  double a_accel_max = 6.0;         // m/s², traction
  double a_brake_max = 8.0;         // m/s², service brakes
  double power_max = 0.0;           // W at the wheels; 0 = no power limit
  double mass = 230.0;              // kg (power limit only)
  double v_max = 20.0;              // m/s: never faster
  double v_max_realtime = 8.0;      // m/s: cap when planning on what is seen
  double kappa_rate_max = 0.5;      // 1/(m·s): steering rate / wheelbase is 0.78; the yaw response lags too; 0 = off
  bool traction_ellipse = true;     // traction shrinks with cornering on an ellipse (rear-wheel drive)
  double understeer = 0.0036;   // rad per m/s²: K of δ = atan(L·κ) + K·v²·κ (the virtual car's, at the lock)
  double steer_reserve = 0.01;  // rad of lock left for the follower to correct with at every planned speed
  double stop_latency = 0.3;    // s from a stop being planned to the brakes acting (loop, link, speed control)
  double stop_margin = 1.0;     // m: every stop planned this short of the end of the known free lane
  // Not configuration keys: the car (car.*).
  double wheelbase = 1.53;
  double max_steer = 0.5;
  SpeedLimits realtime() const;
  SpeedLimits known() const;
};

struct MissionConfig {
  int laps = 2;                              // trackdrive laps (FSAC 2017: 2, FSG: 10); autocross is 1
  double stop_decel = 4.0;                   // m/s²: braking to standstill after the finish
  double stop_distance = 25.0;               // m: stop within this after the finish line (trackdrive, skid pad)
  double acceleration_length = 75.0;         // m: start line to finish line
  double acceleration_stop_distance = 70.0;  // m: stop within this after the finish (the braking zone is 100 m)
  double acceleration_stop_decel = 7.0;      // m/s²: braking after the acceleration finish (zones can be short)
  double acceleration_start_offset = 0.0;    // m from the start pose to the start line when no timing cones are seen
  double open_end_sight = 12.0;              // m: a plan ending this near with no cone beyond is an open layout's end
  double open_end_min_travel = 20.0;         // m driven before an end of the track is believed
  double open_end_settle = 0.5;              // s of unbroken cone updates before an end of the track is believed
  double open_end_confirm = 3.0;             // m driven with the end in sight on every fresh plan before it is believed
  double ebs_trigger_distance = 40.0;        // m past the start line where the EBS test asks for Emergency
  double skidpad_exit_length = 25.0;         // m of exit lane past the crossing
  double skidpad_entry_speed = 4.0;          // m/s until the circles are fitted
  double inspection_duration = 25.0;         // s of steering sweep
  double inspection_speed = 1.0;             // m/s (wheels turning)
  double inspection_period = 4.0;            // s per steering sweep
  double inspection_amplitude = 0.8;         // share of the steering limit swept
};

// The laps a mission times, as the timekeeper counts line crossings: trackdrive `trackdrive_laps`, skid pad 4
// circles, every other mission one run.
inline int timed_laps(Mission mission, int trackdrive_laps) {
  switch (mission) {
    case Mission::Trackdrive:
      return trackdrive_laps;
    case Mission::Skidpad:
      return 4;
    default:
      return 1;
  }
}

// Target speed while stopping after the finish: v² = 2·a·(d_stop − travelled), with a the larger of the
// configured deceleration and what stopping within 80 % of `max_distance` from `v_finish` needs.
double stop_speed(double v_finish, double travelled, double decel, double max_distance);

}  // namespace fsd
