#pragma once
// A hand-made world for testing one mission class alone (control/mission_*.hpp): the car's state, a cone map
// and the real-time plan, as the Autopilot would hand them over in MissionInput. No planner, no follower, no
// car model: the test moves the car where it wants it.
#include <cmath>
#include <optional>
#include <vector>

#include "control/missions/mission_run.hpp"
#include "tests/cone_at.hpp"

namespace fsd::test {

struct MissionWorld {
  VehicleState state;
  bool has_state = true;  // false: no fused state yet
  bool placed = false;    // move() was called
  std::vector<Cone> cones;
  std::uint64_t cones_seq = 0;
  Stamp cones_stamp = -1, cones_unbroken_since = -1;
  std::optional<Path> plan;
  bool plan_ok = false;
  bool gnss_ok = true;
  bool gnss_seen = true;  // false: a car without satellites
  bool map_matched = false;
  double odometer = 0;
  double progress_s = 0;

  // A new cone map at time t (updates at 10 Hz count as unbroken).
  void see(Stamp t, std::vector<Cone> map) {
    cones = std::move(map);
    ++cones_seq;
    if (cones_stamp < 0 || t - cones_stamp > 0.3) cones_unbroken_since = t;
    cones_stamp = t;
  }
  // The car at p heading yaw at speed v (time t); the odometer runs with it.
  void move(Stamp t, const Vec2& p, double yaw, double v) {
    if (placed) odometer += (p - state.pose.position()).norm();
    placed = true;
    state.stamp = t;
    state.pose = Pose2{p.x(), p.y(), yaw};
    state.vx = v;
  }
  MissionInput input(Stamp now) const {
    MissionInput in;
    in.now = now;
    in.state = has_state ? &state : nullptr;
    in.cones = &cones;
    in.cones_seq = cones_seq;
    in.cones_stamp = cones_stamp;
    in.cones_unbroken_since = cones_unbroken_since;
    in.plan = plan ? &*plan : nullptr;
    in.plan_ok = plan_ok;
    in.gnss_ok = gnss_ok;
    in.gnss_seen = gnss_seen;
    in.map_matched = map_matched;
    in.odometer = odometer;
    in.progress_s = progress_s;
    return in;
  }
};

// A follower's result at arc length s on the mission's path.
inline FollowResult followed_at(double s) {
  FollowResult f;
  f.ok = true;
  f.s = s;
  return f;
}

}  // namespace fsd::test
