#pragma once
// The last check before a command goes out (DESIGN.md §5c): the car's motion over the next second is predicted —
// the follower's law steering a kinematic bicycle whose wheels turn at the steering's rate after its dead time and
// whose path widens with the understeer and whose rear axle slips as the follower expects, at the speeds the
// follower asks (reached at the car's acceleration and braking) — and its body swept against the mapped cones. A
// predicted contact caps the speed to what stops the car, braking after the latency, before it happens; as the car
// slows the prediction is made again, so a contact that came from speed goes away and the cap with it.
#include <optional>
#include <vector>

#include "common/types.hpp"
#include "control/planning/footprint.hpp"
#include "control/planning/path.hpp"
#include "control/tracking/follower.hpp"

namespace fsd {

struct ContactGuardConfig {
  bool enabled = true;
  double horizon = 1.0;       // s of predicted motion
  double dt = 0.05;           // s between predicted poses
  double steer_rate = 1.2;    // rad/s of the steering actuator
  double steer_delay = 0.05;  // s before a new steering command moves the wheels
  double understeer = 0.0;    // rad per m/s² (δ = atan(L·κ) + K·v²·κ): not a key, control.speed.understeer
  double margin = 0.0;        // m: a predicted clearance below this is a contact
  double decel = 6.0;         // m/s² the cap brakes at, and the prediction slows at
  double accel = 4.0;         // m/s² the prediction speeds up at
  double latency = 0.2;       // s before the brakes act
  double range = 15.0;        // m: cones farther from the car are not checked
};

struct GuardResult {
  bool contact = false;          // a contact is predicted within the horizon
  double speed_cap = 1e9;        // m/s (1e9: no cap)
  double distance = 0;           // m driven to the predicted contact
  Vec2 cone = Vec2::Zero();      // the cone it would touch (map frame)
  std::vector<Pose2> predicted;  // the predicted poses, for display
};

class ContactGuard {
 public:
  explicit ContactGuard(ContactGuardConfig config = {}) : config_(config) {}

  // `follower`: a copy of the follower in use (its law and gains), `command` the command it just gave, `speed` the
  // target speed it asks. `cones`: map frame.
  GuardResult check(const Path& path, PathFollower follower, const VehicleState& state, const ControlCommand& command,
                    const std::vector<Obstacle>& cones, const Body& body, double wheelbase, double max_steer) const;

  const ContactGuardConfig& config() const { return config_; }
  void set_config(const ContactGuardConfig& c) { config_ = c; }

 private:
  ContactGuardConfig config_;
};

}  // namespace fsd
