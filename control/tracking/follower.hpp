#pragma once
// Path following (paper §IV, its reference [1]): pure pursuit, Stanley, or a kinematic LQR, selected by
// config. Each cycle predicts the pose forward (kinematic bicycle on the measured steering) by the state's age
// (now − its stamp) and the actuation latency, projects it on the path, computes the front wheel angle with the
// selected law and takes the target speed from the path a little ahead. Output: ControlCommand (steering angle,
// target speed).
#include <optional>
#include <string>

#include "common/types.hpp"
#include "control/planning/path.hpp"

namespace fsd {

enum class FollowerType { PurePursuit, Stanley, Lqr };
std::optional<FollowerType> follower_type_from_string(const std::string& s);
std::string to_string(FollowerType t);

struct FollowerConfig {
  std::string type = "lqr";  // pure_pursuit | stanley | lqr
  double wheelbase = 1.53;   // m, rear axle to front axle
  double max_steer = 0.5;    // rad, front wheel angle limit (≈ 29°); must match the car
  double latency = 0.06;     // s: sensing-to-wheel delay the pose is predicted over
  // Pure pursuit: look-ahead distance k·v + L0 along the path, clamped.
  double pp_gain = 0.2;  // s
  double pp_min = 2.5;   // m (L0 and the floor)
  double pp_max = 12.0;  // m
  // Stanley: δ = ψe − atan(k·e / (v_soft + v)), heading and lateral error at the front axle.
  double stanley_gain = 2.0;       // 1/s
  double stanley_softening = 1.0;  // m/s
  // Kinematic LQR on (lateral error, heading error) with curvature feed-forward.
  double lqr_q_lateral = 1.0;        // 1/m²
  double lqr_q_heading = 1.0;        // 1/rad²
  double lqr_r = 3.0;                // 1/rad²
  double lqr_dt = 0.05;              // s: discretisation of the error model
  double lqr_sideslip_gain = 0.008;  // rad per m/s²: rear slip angle per lateral acceleration (virtual car: 0.004
                                     // from its tyres' linear stiffness, 0.008 measured nearer the grip limit)
  double lqr_preview = 0.1;          // s: curvature feed-forward taken this far ahead (steering actuator lag)
  double speed_preview = 0.4;        // s: the target speed is the path's speed this far ahead
  double speed_lead = 0.0;           // s: plus the path's acceleration times this (≈ 1 / the VCU speed-loop gain)
  double speed_lead_brake = 0.0;     // s: the same where the path slows down (braking already at the friction
                                     // circle's limit; a lead there over-brakes into the corner entry)
  // Tracking governor: farther than governor_offset from the path, or with the steering at its limit, the
  // target speed is held at or below the car's speed, less governor_gain per metre beyond the offset (but not
  // below governor_floor, so that a car standing off the line still drives back onto it). A car
  // pushed wide at the grip limit only gets back by slowing down; accelerating there spins or leaves the track.
  double governor_offset = 0.5;  // m (0.5 m is the largest allowed cross-track error on lap 2)
  double governor_gain = 3.0;    // m/s per m beyond the offset; 0 = governor off
  double governor_floor = 2.0;   // m/s: the governor never asks for less
  double search_window = 15.0;   // m: projection window around the last foot point on the same path
  // Not a configuration key: the car's understeer gradient (control.speed.understeer), whose steer K·v²·κ the LQR
  // adds to its curvature feed-forward (a car that understeers needs more lock at speed than atan(L·κ)).
  double understeer = 0.0;  // rad per m/s²
  double max_offset = 4.0;  // m: farther from the path is "off path" (result not ok)
};

struct FollowResult {
  ControlCommand command;      // steering and target speed (stamped now)
  bool ok = false;             // false: no path, or the car is off it; the command then holds straight, stops
  double cross_track = 0;      // m, rear axle from the path, left positive (of the predicted pose)
  double heading_error = 0;    // rad, car heading minus path heading
  double s = 0;                // m, arc length of the projection
  Vec2 target = Vec2::Zero();  // look-ahead point (pure pursuit) or foot point, map frame
};

// Kinematic bicycle step: rear-axle pose after dt at speed v with front wheel angle delta.
Pose2 predict_bicycle(const Pose2& pose, double v, double delta, double wheelbase, double dt);

class PathFollower {
 public:
  explicit PathFollower(FollowerConfig config = {});

  // One control cycle. speed_cap bounds the target speed (mission or supervisor limits).
  FollowResult follow(const Path& path, const VehicleState& state, Stamp now, double speed_cap);
  // Forgets the projection hint (a new mission path). `near_s`: where along the next path the car is known to be
  // (a figure of eight passes its crossing five times: a search over the whole path may pick the wrong pass).
  void reset(std::optional<double> near_s = std::nullopt) {
    hint_.reset();
    near_s_ = near_s;
  }

  const FollowerConfig& config() const { return config_; }
  // The rear axle's slip angle this law steers for at speed v on curvature kappa: the LQR's sideslip feed-forward
  // (lqr_sideslip_gain × v²κ); the geometric laws assume none.
  double expected_sideslip(double v, double kappa) const {
    return type_ == FollowerType::Lqr ? config_.lqr_sideslip_gain * v * v * kappa : 0.0;
  }
  void set_config(const FollowerConfig& c);  // unknown type strings keep the current law

 private:
  double pure_pursuit(const Path& path, const Pose2& pose, double v, double s, Vec2& target) const;
  double stanley(const Path& path, const Pose2& pose, double v, double s) const;
  double lqr(const Path& path, const PathProjection& proj, const Pose2& pose, double v) const;

  FollowerConfig config_;
  FollowerType type_ = FollowerType::Lqr;
  struct Hint {
    Stamp stamp;
    std::size_t size;
    double length;
    double s;
  };
  std::optional<Hint> hint_;
  std::optional<double> near_s_;
};

}  // namespace fsd
