#pragma once
// The virtual car's VCU firmware stand-in: the other end of the VCU protocol and owner of the autonomous-system
// state machine of the Formula Student rules (AS Off, Ready, Driving, Emergency, Finished) with the RES and the
// EBS. It decodes the daemon's Commands (each one is the heartbeat), sends Status frames at its rate, and gives
// the vehicle model what the actuators should do. Pure: no I/O, no threads, time only from its arguments.
//
//   Off      → Ready      the stack requests Ready, a mission is selected, ASMS on, EBS brakes pressurised
//   Ready    → Driving    RES go, accepted only after ≥ ready_to_drive_s in Ready (earlier presses are ignored)
//   Driving  → Finished   the stack requests Finished and the car is at standstill
//   any      → Emergency  RES emergency; the stack's emergency request; heartbeat lost > heartbeat_timeout
//                         in Ready or Driving; ASMS switched off while Driving. Emergency is latched (EBS on)
//   Emergency, Finished, Ready → Off   only by switching the ASMS off (set_asms(false))
#include <cstdint>
#include <random>
#include <span>
#include <string>
#include <vector>

#include "common/config.hpp"
#include "common/types.hpp"
#include "common/wire/vcu_protocol.hpp"
#include "drivers/sim/sensors/sink.hpp"
#include "drivers/sim/vehicle/vehicle_truth.hpp"

namespace fsd::sim {

struct VcuStandinConfig {
  double status_rate_hz = 100.0;
  double heartbeat_timeout = 0.1;   // s without a valid Command before the EBS fires (Ready/Driving)
  double ready_to_drive_s = 5.0;    // minimum time in Ready before RES go is accepted (FS rules: 5 s)
  double res_go_at_s = -1.0;        // simulated RES operator presses go this long after Ready; < 0: never
  bool asms_on = true;              // autonomous system master switch
  bool brakes_pressurised = true;   // EBS tanks charged (a condition of Ready)
  double standstill_speed = 0.05;   // m/s: the car counts as stopped below this (for Finished)
  double wheel_speed_noise = 0.01;  // m/s, standard deviation of each wheel speed
  double steering_noise = 0.0005;   // rad, standard deviation of the measured steering angle
  int seed = 1;
};
const ConfigSection<VcuStandinConfig>& vcu_standin_section();

// What the VCU makes the actuators do; the vehicle model's ActuatorCommand has the same fields.
struct ActuatorOutput {
  double steering_request = 0;  // front wheel angle, rad, left positive
  double target_speed = 0;      // m/s for the VCU's speed controller
  bool max_brake = false;       // maximum service braking
  bool ebs = false;             // emergency brake system engaged
  bool drive_enabled = false;   // tractive system may drive (AS Driving only)
};

struct AsTransition {
  Stamp t = 0;
  AsState from = AsState::Off, to = AsState::Off;
  std::string why;
};

struct VcuStandinCounters {
  std::uint64_t commands = 0;  // valid Commands received
  std::uint64_t statuses_sent = 0;
  std::uint64_t go_ignored = 0;  // RES go pressed outside Ready or before ready_to_drive_s
  wire::vcu::DecoderCounters rx;
};

class VcuStandin {
 public:
  VcuStandin(VcuStandinConfig cfg, ByteSink status_sink);

  // Bytes from the daemon, arriving at time t (any chunking).
  void feed(Stamp t, std::span<const std::uint8_t> bytes);
  // Runs the state machine at time t, sends a Status when one is due, and returns the actuator output.
  const ActuatorOutput& step(Stamp t, const VehicleTruth& truth);

  // The simulated RES and the ASMS.
  void press_go(Stamp t);
  void press_emergency(Stamp t);
  void set_asms(Stamp t, bool on);

  AsState state() const { return state_; }
  Mission mission() const { return mission_; }
  const ActuatorOutput& output() const { return out_; }
  const VcuStatus& last_status() const { return status_; }  // the last Status sent (before wire quantisation)
  const std::vector<AsTransition>& transitions() const { return transitions_; }
  VcuStandinCounters counters() const;
  const VcuStandinConfig& config() const { return cfg_; }

 private:
  void on_command(Stamp t, const wire::vcu::Command& c);
  void enter(Stamp t, AsState to, std::string why, std::uint32_t cause = 0);
  bool heartbeat_lost(Stamp t) const;
  void update_output();
  void send_status(Stamp t, const VehicleTruth& truth);

  VcuStandinConfig cfg_;
  ByteSink sink_;
  wire::vcu::Decoder decoder_;
  wire::vcu::Sequencer seq_;
  std::optional<wire::vcu::SendSchedule> schedule_;  // starts at the first step
  std::mt19937_64 rng_;
  std::normal_distribution<double> unit_noise_{0.0, 1.0};

  Stamp feed_t_ = 0;
  std::optional<wire::vcu::Command> command_;
  Stamp command_t_ = 0;

  AsState state_ = AsState::Off;
  Mission mission_ = Mission::None;
  Stamp ready_since_ = 0;
  bool auto_go_done_ = false;
  bool res_go_ = false;
  bool res_emergency_ = false;
  std::uint32_t emergency_cause_ = 0;
  bool ready_refused_ = false;
  double held_steering_ = 0;
  std::uint64_t rx_rejected_reported_ = 0;

  ActuatorOutput out_;
  VcuStatus status_;
  std::vector<AsTransition> transitions_;
  VcuStandinCounters counters_;
};

}  // namespace fsd::sim
