#pragma once
// A closed loop for the control tests: the daemon's own Stack (daemon/stack/stack.hpp) driving the bicycle car of
// bicycle_sim.hpp, fed as the virtual car feeds it but without its cost: the true state and the true cones as truth
// frames (the truth sources: an ideal detector with the harness's sensor range and no noise, at 10 Hz), NMEA epochs
// at 50 Hz whose fix quality follows gnss_good(t), and a VCU stand-in with the Formula Student AS state machine
// (Off → Ready on request, Ready → Driving on RES go 5 s later, Driving → Finished on request at standstill,
// → Emergency on request with the EBS braking) speaking the VCU protocol's Status frames.
// Records what the scorecard would: laps, cone hits, stop position, AS state, faults.
#include <cmath>
#include <functional>
#include <numbers>
#include <set>
#include <span>
#include <string>

#include "common/track.hpp"
#include "common/wire/nmea.hpp"
#include "common/wire/vcu_protocol.hpp"
#include "control/autopilot.hpp"
#include "daemon/feeders/truth_frames.hpp"
#include "daemon/stack/settings.hpp"
#include "daemon/stack/stack.hpp"
#include "drivers/sim/world/reference_line.hpp"
#include "tests/control/bicycle_sim.hpp"
#include "tests/control/track_truth.hpp"

namespace fsd::test {

// The autopilot's configuration for this harness's car: the defaults with μ 1.2, and what only the virtual car's
// tyre model justifies switched off.
inline AutopilotConfig bicycle_autopilot_config() {
  AutopilotConfig c;
  c.speed.mu = 1.2;
  // The lap-2 LQR gains (control.lap2) are tuned on the virtual car's dynamic model, whose tyre slip damps the
  // steering loop; this kinematic bicycle has none and oscillates into the cones with them (q 3, r 1). Its lap 2
  // is driven with the lap-1 gains.
  c.lap2.lqr_q_lateral = c.follower.lqr_q_lateral;
  c.lap2.lqr_q_heading = c.follower.lqr_q_heading;
  c.lap2.lqr_r = c.follower.lqr_r;
  // No tyres, no slip: the sideslip feed-forward would only bias this bicycle's heading, and it does not understeer.
  c.follower.lqr_sideslip_gain = 0;
  c.speed.understeer = c.follower.understeer = c.guard.understeer = 0;
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
  // The Stack's compute-time clocks (empty: the wall clock, the thread's CPU time) and its lap-2 worker thread.
  std::function<double()> wall_clock;
  std::function<double()> cpu_clock;
  bool lap_build_worker = false;
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
      : track_(track),
        truth_(track),
        options_(options),
        stack_(stack_config(track, options), stack_options(mission, config, options)) {
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
    const auto cones = encode_truth_cones(true_cones());
    stack_.feed({RawChannel::TruthCones, 0.0, cones});
    while (car_.t < options_.max_time) {
      const double t = car_.t;
      // VCU stand-in: the AS state machine, its Status frame to the stack.
      if (vcu_.as_state == AsState::Ready && t >= go_time_) vcu_.as_state = AsState::Driving;
      vcu_.stamp = t;
      vcu_.steering_measured = car_.delta;
      const auto status = wire::vcu::encode(vcu_, vcu_seq_++);
      stack_.feed({RawChannel::VcuRx, t, status});
      // The GNSS-INS epoch: good, or degraded to a single-point fix.
      const std::string nmea = nmea_epoch(t, options_.gnss_good(t));
      stack_.feed({RawChannel::Nmea, t, std::span(reinterpret_cast<const std::uint8_t*>(nmea.data()), nmea.size())});
      // The truth: the state (with the planner stall), and the ideal detector's scan at 10 Hz while the LiDAR lives.
      const auto state = encode_truth_state(
          {car_.state(), options_.planner_stalled(t), static_cast<std::uint32_t>(hit_.size()), vcu_.as_state});
      stack_.feed({RawChannel::TruthState, t, state});
      if (t + 1e-9 >= next_perception) {
        next_perception += options_.perception_period;
        if (options_.lidar_alive(t)) stack_.feed({RawChannel::TruthScan, t, {}});
      }
      const ControlOutput out = stack_.step(t).out;
      if (options_.observe) options_.observe(t, out, car_);
      outputs_.push_back(out.request);
      if (out.lap) laps_.push_back(*out.lap);
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
      records_.push_back({t, car_.pose.position(), car_.v, truth_.centre_distance(car_.pose.position()), out.source,
                          static_cast<int>(laps_.size())});
      const bool done_state = vcu_.as_state == AsState::Finished || vcu_.as_state == AsState::Emergency;
      if (done_state && car_.v < 0.01) break;
    }
  }

  Autopilot& autopilot() { return stack_.autopilot(); }
  Stack& stack() { return stack_; }
  const test::BicycleSim& car() const { return car_; }
  AsState as_state() const { return vcu_.as_state; }
  const std::vector<LapEvent>& laps() const { return laps_; }
  const std::vector<CycleRecord>& records() const { return records_; }
  const TrackTruth& truth() const { return truth_; }
  int cones_hit() const { return static_cast<int>(hit_.size()); }
  const std::vector<std::pair<double, Vec2>>& hits() const { return hits_; }
  // Distance the car rolled while the AS was not Driving (nor braking in Emergency).
  double moved_outside_driving() const { return moved_outside_; }
  std::optional<double> finished_at() const { return finished_at_; }
  std::optional<double> emergency_at() const { return emergency_at_; }

  // Cross-track error (RMS, max) over the cycles of lap `lap` (1-based, crossing to crossing) to this harness's
  // centre line (track_truth.hpp); with `reference` (the scorecard's, sim::ReferenceLine), to the nearer of the
  // two at each cycle: two independent definitions from the same cones, which differ only where the centre of a
  // corner is itself ambiguous.
  std::pair<double, double> lap_cte(int lap, const sim::ReferenceLine* reference = nullptr) const {
    double sum = 0, mx = 0;
    long n = 0;
    const double t0 = lap >= 2 ? laps_[static_cast<std::size_t>(lap - 2)].t : 0.0;
    const double t1 = laps_[static_cast<std::size_t>(lap - 1)].t;
    for (const auto& r : records_)
      if (r.t > t0 && r.t <= t1) {
        const double d = reference ? std::min(r.centre_distance, reference->distance(r.position)) : r.centre_distance;
        sum += d * d;
        mx = std::max(mx, d);
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

  static Config stack_config(const Track& track, const HarnessOptions& o) {
    Config c(config_schema());
    // The harness feeds the truth frames a simulator would: the truth sources, whatever the defaults.
    c.set("run.perception_source", std::string("truth"), "harness");
    c.set("run.localization_source", std::string("truth"), "harness");
    c.set("run.colours", track.convention.name, "harness");
    c.set("run.truth_perception.range", o.sensor_range, "harness");
    c.set("run.truth_perception.position_noise", 0.0, "harness");
    c.set("run.truth_perception.min_range", 0.0, "harness");
    c.set("drivers.gnss.use_first_fix", false, "harness");
    c.set("drivers.gnss.origin_lat_deg", kLat, "harness");
    c.set("drivers.gnss.origin_lon_deg", kLon, "harness");
    c.set("drivers.gnss.emit_on", std::string("HDT"), "harness");
    return c;
  }
  static StackOptions stack_options(Mission mission, const AutopilotConfig& config, const HarnessOptions& h) {
    StackOptions o;
    o.mission = mission;
    o.laps = config.mission.laps;
    o.simulator = true;
    o.control = config;
    o.wall_clock = h.wall_clock;
    o.cpu_clock = h.cpu_clock;
    o.lap_build_worker = h.lap_build_worker;
    return o;
  }
  std::vector<Cone> true_cones() const {
    std::vector<Cone> out;
    for (std::size_t i = 0; i < track_.cones.size(); ++i) {
      Cone c;
      c.position = Vec3(track_.cones[i].position.x(), track_.cones[i].position.y(), 0);
      c.colour = track_.cones[i].colour;
      c.id = static_cast<std::uint32_t>(i + 1);
      out.push_back(c);
    }
    return out;
  }
  // GGA (RTK fixed, or a single-point fix when bad) and HDT: what the GNSS driver needs to call the fix good. The
  // position is the origin's: the harness localizes on the truth.
  std::string nmea_epoch(double t, bool good) const {
    const auto lat = nmea::format_latitude(kLat, 6), lon = nmea::format_longitude(kLon, 6);
    const std::string hhmmss = nmea::format_time_of_day(36000.0 + t, 2);
    std::string out =
        nmea::build("GPGGA", std::vector<std::string>{hhmmss, lat.value, lat.hemisphere, lon.value, lon.hemisphere,
                                                      good ? "4" : "1", "12", "0.80", "400.000", "M", "0.000", "M",
                                                      good ? "0.5" : "", good ? "0000" : ""});
    const double north_deg =
        std::fmod(std::fmod(90.0 - car_.pose.yaw * 180.0 / std::numbers::pi, 360.0) + 360.0, 360.0);
    out += nmea::build("GPHDT", std::vector<std::string>{nmea::format_fixed(north_deg, 3), "T"});
    return out;
  }
  static constexpr double kLat = 47.0, kLon = 8.0;

  Track track_;
  TrackTruth truth_;
  HarnessOptions options_;
  Stack stack_;
  std::uint16_t vcu_seq_ = 0;
  test::BicycleSim car_;
  VcuStatus vcu_;
  double go_time_ = 1e9;
  std::set<std::size_t> hit_;
  std::vector<std::pair<double, Vec2>> hits_;  // (time, cone) of each cone's first hit
  std::vector<AsRequest> outputs_;
  std::vector<LapEvent> laps_;
  std::vector<CycleRecord> records_;
  double moved_outside_ = 0;
  std::optional<double> finished_at_, emergency_at_;
};

}  // namespace fsd::test
