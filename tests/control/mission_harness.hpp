#pragma once
// A closed loop for the Autopilot, written for the tests: the bicycle car of bicycle_sim.hpp, "perception"
// that adds the true cones within sensor range to a cone map at 10 Hz, a fused pose and GNSS at 50 Hz, and a
// VCU stand-in with the Formula Student AS state machine (Off → Ready on request, Ready → Driving on RES go
// 5 s later, Driving → Finished on request at standstill, → Emergency on request with the EBS braking).
// Records what the scorecard would: laps, cone hits, stop position, AS state, faults.
#include <functional>
#include <set>

#include "control/autopilot.hpp"
#include "tests/control/bicycle_sim.hpp"
#include "tests/control/track_truth.hpp"

namespace fsd::test {

// The autopilot's configuration for this harness's car: the defaults with μ 1.2, and what only the virtual car's
// tyre model justifies switched off.
inline AutopilotConfig bicycle_autopilot_config() {
  AutopilotConfig c;
  c.speed.mu = 1.2;
  // The planner's wall-clock budget is checked by the supervisor tests; here a loaded machine must not turn
  // a slow plan into a stop (the runs would stop being reproducible).
  c.supervisor.check_plan_time = false;
  // The lap-2 LQR gains (control.lap2) are tuned on the virtual car's dynamic model, whose tyre slip damps the
  // steering loop; this kinematic bicycle has none and oscillates into the cones with them (q 3, r 1). Its lap 2
  // is driven with the lap-1 gains.
  c.lap2.lqr_q_lateral = c.follower.lqr_q_lateral;
  c.lap2.lqr_q_heading = c.follower.lqr_q_heading;
  c.lap2.lqr_r = c.follower.lqr_r;
  // No tyres, no slip: the sideslip feed-forward would only bias this bicycle's heading.
  c.follower.lqr_sideslip_gain = 0;
  return c;
}

struct HarnessOptions {
  double sensor_range = 20.0;
  double control_period = 0.02;
  double perception_period = 0.1;
  double go_delay = 5.0;
  double max_time = 200.0;
  // Fault injection by time: GNSS quality, LiDAR output, planner stall.
  std::function<bool(double)> gnss_good = [](double) { return true; };
  std::function<bool(double)> lidar_alive = [](double) { return true; };
  std::function<bool(double)> planner_stalled = [](double) { return false; };
  // Sees every cycle's output (checks inside the loop, debugging).
  std::function<void(double, const ControlOutput&, const BicycleSim&)> observe;
};

struct CycleRecord {
  double t;
  Vec2 position;
  double speed;
  double centre_distance;
  PathSource source;
  int laps_done;
};

class MissionHarness {
 public:
  MissionHarness(const Track& track, Mission mission, AutopilotConfig config, HarnessOptions options = {})
      : track_(track), truth_(track), options_(options), autopilot_(config, mission, track.convention) {
    car_.pose = track.start;
    car_.wheelbase = config.follower.wheelbase;
    car_.max_steer = config.follower.max_steer;
    car_.accel = config.speed.a_accel_max;
    car_.brake = 9.0;
    vcu_.as_state = AsState::Off;
    vcu_.mission = mission;
  }

  // Runs until the AS is Finished or Emergency and the car stands, or max_time.
  void run() {
    double next_perception = 0;
    while (car_.t < options_.max_time) {
      const double t = car_.t;
      // VCU stand-in: the AS state machine.
      if (vcu_.as_state == AsState::Ready && t >= go_time_) vcu_.as_state = AsState::Driving;
      vcu_.stamp = t;
      vcu_.steering_measured = car_.delta;
      autopilot_.on_vcu(vcu_);
      // Perception at 10 Hz: the true cones within range join the map.
      if (t + 1e-9 >= next_perception) {
        next_perception += options_.perception_period;
        if (options_.lidar_alive(t)) {
          for (std::size_t i = 0; i < track_.cones.size(); ++i)
            if ((track_.cones[i].position - car_.pose.position()).norm() <= options_.sensor_range) seen_.insert(i);
          std::vector<Cone> map;
          for (const auto i : seen_) {
            Cone c;
            c.position = Vec3(track_.cones[i].position.x(), track_.cones[i].position.y(), 0);
            c.colour = track_.cones[i].colour;
            c.id = static_cast<std::uint32_t>(i + 1);
            map.push_back(c);
          }
          autopilot_.on_cones(t, std::move(map));
        }
      }
      autopilot_.on_state(car_.state());
      autopilot_.on_gnss(t, options_.gnss_good(t));
      autopilot_.set_planner_stalled(options_.planner_stalled(t));
      const ControlOutput out = autopilot_.step(t);
      if (options_.observe) options_.observe(t, out, car_);
      outputs_.push_back(out.request);
      if (out.lap) laps_.push_back(*out.lap);
      max_plan_time_ = std::max(max_plan_time_, out.planning_time);
      handle_request(out.request, t);
      ControlCommand cmd = out.command;
      if (vcu_.as_state == AsState::Emergency) {  // EBS: full braking, whatever the stack says
        cmd.target_speed = 0;
        cmd.brake_hard = true;
      }
      if (vcu_.as_state != AsState::Driving && vcu_.as_state != AsState::Emergency) cmd.target_speed = 0;
      const bool outside = vcu_.as_state != AsState::Driving && vcu_.as_state != AsState::Emergency;
      const Vec2 before = car_.pose.position();
      car_.command(cmd);
      for (int k = 0; k < static_cast<int>(std::round(options_.control_period / car_.dt)); ++k) {
        car_.step();
        count_hits();
      }
      if (outside) moved_outside_ += (car_.pose.position() - before).norm();
      records_.push_back({t, car_.pose.position(), car_.v, truth_.centre_distance(car_.pose.position()),
                          out.source, static_cast<int>(laps_.size())});
      const bool done_state = vcu_.as_state == AsState::Finished || vcu_.as_state == AsState::Emergency;
      if (done_state && car_.v < 0.01) break;
    }
  }

  Autopilot& autopilot() { return autopilot_; }
  const test::BicycleSim& car() const { return car_; }
  AsState as_state() const { return vcu_.as_state; }
  const std::vector<LapEvent>& laps() const { return laps_; }
  const std::vector<CycleRecord>& records() const { return records_; }
  const TrackTruth& truth() const { return truth_; }
  int cones_hit() const { return static_cast<int>(hit_.size()); }
  const std::vector<std::pair<double, Vec2>>& hits() const { return hits_; }
  // Distance the car rolled while the AS was not Driving (nor braking in Emergency).
  double moved_outside_driving() const { return moved_outside_; }
  double max_plan_time() const { return max_plan_time_; }
  std::optional<double> finished_at() const { return finished_at_; }
  std::optional<double> emergency_at() const { return emergency_at_; }

  // Cross-track error to the true centre line over the cycles of lap `lap` (1-based, crossing to crossing).
  std::pair<double, double> lap_cte(int lap) const {
    double sum = 0, mx = 0;
    long n = 0;
    const double t0 = lap >= 2 ? laps_[static_cast<std::size_t>(lap - 2)].t : 0.0;
    const double t1 = laps_[static_cast<std::size_t>(lap - 1)].t;
    for (const auto& r : records_)
      if (r.t > t0 && r.t <= t1) {
        sum += r.centre_distance * r.centre_distance;
        mx = std::max(mx, r.centre_distance);
        ++n;
      }
    return {n ? std::sqrt(sum / static_cast<double>(n)) : 0.0, mx};
  }

 private:
  void handle_request(AsRequest r, double t) {
    if (r == AsRequest::Ready && vcu_.as_state == AsState::Off) {
      vcu_.as_state = AsState::Ready;
      go_time_ = t + options_.go_delay;
    }
    if (r == AsRequest::Finished && vcu_.as_state == AsState::Driving) {
      EXPECT_LT(car_.v, 0.2) << "Finished requested while moving";
      vcu_.as_state = AsState::Finished;
      finished_at_ = t;
    }
    if (r == AsRequest::Emergency && vcu_.as_state != AsState::Emergency) {
      vcu_.as_state = AsState::Emergency;
      emergency_at_ = t;
    }
  }

  // A cone is hit when it is inside the car's footprint (rear overhang 0.3 m, front 0.7 m past the front axle,
  // 1.4 m wide) grown by the cone's base radius.
  void count_hits() {
    const double r = 0.114;
    for (std::size_t i = 0; i < track_.cones.size(); ++i) {
      const Vec2 l = car_.pose.inverse_transform(track_.cones[i].position);
      if (l.x() > -0.3 - r && l.x() < car_.wheelbase + 0.7 + r && std::abs(l.y()) < 0.7 + r && hit_.insert(i).second)
        hits_.push_back({car_.t, track_.cones[i].position});
    }
  }

  Track track_;
  TrackTruth truth_;
  HarnessOptions options_;
  Autopilot autopilot_;
  test::BicycleSim car_;
  VcuStatus vcu_;
  double go_time_ = 1e9;
  std::set<std::size_t> seen_, hit_;
  std::vector<std::pair<double, Vec2>> hits_;  // (time, cone) of each cone's first hit
  std::vector<AsRequest> outputs_;
  std::vector<LapEvent> laps_;
  std::vector<CycleRecord> records_;
  double moved_outside_ = 0;
  double max_plan_time_ = 0;
  std::optional<double> finished_at_, emergency_at_;
};

}  // namespace fsd::test
