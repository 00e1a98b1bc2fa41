#include "drivers/sim/vcu_standin.hpp"

#include <fmt/format.h>

#include "common/logging.hpp"

namespace fsd::sim {

namespace vcu = wire::vcu;

namespace {
constexpr std::size_t kMaxTransitions = 256;
constexpr Duration kTimeSlack = 1e-9;  // rounding of the caller's time steps
}  // namespace

const ConfigSection<VcuStandinConfig>& vcu_standin_section() {
  static const auto s =
      ConfigSection<VcuStandinConfig>("sim.vcu")
          .number("status_rate_hz", &VcuStandinConfig::status_rate_hz, 50.0, 1000.0, "Hz",
                  "Rate of the simulated VCU's Status frames.")
          .number("heartbeat_timeout", &VcuStandinConfig::heartbeat_timeout, 0.02, 2.0, "s",
                  "No valid Command for this long in AS Ready or Driving fires the EBS (AS Emergency).")
          .number("ready_to_drive_s", &VcuStandinConfig::ready_to_drive_s, 0.0, 60.0, "s",
                  "Minimum time in AS Ready before a RES go is accepted (FS rules: 5 s).")
          .number("res_go_at_s", &VcuStandinConfig::res_go_at_s, -1.0, 3600.0, "s",
                  "The simulated RES operator presses go this long after AS Ready (headless runs); negative: never. "
                  "A press before ready_to_drive_s is ignored, as on the car.")
          .boolean("asms_on", &VcuStandinConfig::asms_on, "Autonomous system master switch on at start.")
          .boolean("brakes_pressurised", &VcuStandinConfig::brakes_pressurised,
                   "EBS brake pressure available (a condition of AS Ready).")
          .number("standstill_speed", &VcuStandinConfig::standstill_speed, 0.0, 1.0, "m/s",
                  "Below this speed the car is at standstill (AS Finished needs it).")
          .number("wheel_speed_noise", &VcuStandinConfig::wheel_speed_noise, 0.0, 1.0, "m/s",
                  "Standard deviation of each reported wheel speed.")
          .number("steering_noise", &VcuStandinConfig::steering_noise, 0.0, 0.1, "rad",
                  "Standard deviation of the reported steering angle.")
          .integer("seed", &VcuStandinConfig::seed, 0, 1000000000, "", "Seed of the measurement noise.");
  return s;
}

VcuStandin::VcuStandin(VcuStandinConfig cfg, ByteSink status_sink)
    : cfg_(cfg),
      sink_(std::move(status_sink)),
      decoder_(vcu::Decoder::Handlers{[this](const vcu::Command& c, std::uint16_t) { on_command(feed_t_, c); }, nullptr,
                                      nullptr}),
      rng_(static_cast<std::uint64_t>(cfg.seed)) {
  if (cfg_.res_go_at_s >= 0 && cfg_.res_go_at_s < cfg_.ready_to_drive_s)
    logger("sim")->warn("sim.vcu.res_go_at_s = {} s is before ready_to_drive_s = {} s: that go will be ignored",
                        cfg_.res_go_at_s, cfg_.ready_to_drive_s);
}

void VcuStandin::feed(Stamp t, std::span<const std::uint8_t> bytes) {
  feed_t_ = t;
  decoder_.feed(bytes);
}

void VcuStandin::on_command(Stamp t, const vcu::Command& c) {
  command_ = c;
  command_t_ = t;
  ++counters_.commands;
}

bool VcuStandin::heartbeat_lost(Stamp t) const {
  return !command_ || t - command_t_ > cfg_.heartbeat_timeout + kTimeSlack;
}

const ActuatorOutput& VcuStandin::step(Stamp t, const VehicleTruth& truth) {
  if (!schedule_) schedule_.emplace(cfg_.status_rate_hz, t);

  if (state_ == AsState::Ready && cfg_.res_go_at_s >= 0 && !auto_go_done_ &&
      t + kTimeSlack >= ready_since_ + cfg_.res_go_at_s) {
    auto_go_done_ = true;
    press_go(t);
  }

  if (state_ != AsState::Emergency) {
    if (command_ && command_->as_request == vcu::AsRequest::Emergency) {
      enter(t, AsState::Emergency, "the stack requested an emergency stop", vcu::kFaultEmergencyRequest);
    } else if ((state_ == AsState::Ready || state_ == AsState::Driving) && heartbeat_lost(t)) {
      enter(t, AsState::Emergency, fmt::format("heartbeat lost for {:.3f} s", t - command_t_),
            vcu::kFaultEmergencyHeartbeat);
    }
  }

  ready_refused_ = false;
  if (state_ == AsState::Off && !heartbeat_lost(t)) {
    mission_ = command_->mission;  // the mission can change only while Off
    if (command_->as_request == vcu::AsRequest::Ready) {
      if (mission_ != Mission::None && cfg_.asms_on && cfg_.brakes_pressurised) {
        ready_since_ = t;
        auto_go_done_ = false;
        enter(t, AsState::Ready, fmt::format("Ready requested, mission {}", to_string(mission_)));
      } else {
        ready_refused_ = true;
      }
    }
  } else if (state_ == AsState::Driving && command_->as_request == vcu::AsRequest::Finished &&
             truth.speed() < cfg_.standstill_speed) {
    enter(t, AsState::Finished, "Finished requested at standstill");
  }

  update_output();
  if (schedule_->due(t)) send_status(t, truth);
  return out_;
}

void VcuStandin::press_go(Stamp t) {
  if (state_ == AsState::Ready && t - ready_since_ + kTimeSlack >= cfg_.ready_to_drive_s) {
    res_go_ = true;
    enter(t, AsState::Driving, "RES go");
    update_output();
    return;
  }
  ++counters_.go_ignored;
  logger("sim")->info("RES go at {:.3f} s ignored in AS {}{}", t, to_string(state_),
                      state_ == AsState::Ready ? fmt::format(" after {:.3f} s", t - ready_since_) : std::string());
}

void VcuStandin::press_emergency(Stamp t) {
  res_emergency_ = true;
  if (state_ != AsState::Emergency) enter(t, AsState::Emergency, "RES emergency", vcu::kFaultEmergencyRes);
  update_output();
}

void VcuStandin::set_asms(Stamp t, bool on) {
  cfg_.asms_on = on;
  if (on) return;
  if (state_ == AsState::Driving) {
    enter(t, AsState::Emergency, "ASMS switched off while driving", vcu::kFaultEmergencyAsms);
  } else if (state_ != AsState::Off) {
    enter(t, AsState::Off, "ASMS switched off");
    res_go_ = res_emergency_ = false;
    emergency_cause_ = 0;
    held_steering_ = 0;
  }
  update_output();
}

void VcuStandin::enter(Stamp t, AsState to, std::string why, std::uint32_t cause) {
  if (transitions_.size() >= kMaxTransitions) transitions_.erase(transitions_.begin());
  logger("sim")->info("VCU AS {} → {} at {:.3f} s: {}", to_string(state_), to_string(to), t, why);
  transitions_.push_back({t, state_, to, std::move(why)});
  state_ = to;
  emergency_cause_ |= cause;
}

void VcuStandin::update_output() {
  out_ = ActuatorOutput{};
  switch (state_) {
    case AsState::Off:
      held_steering_ = 0;
      break;
    case AsState::Ready:
      out_.max_brake = true;  // FS rules: service brake engaged in AS Ready
      break;
    case AsState::Driving:
      held_steering_ = command_->steering;
      out_.target_speed = command_->target_speed;
      out_.max_brake = command_->brake_hard;
      out_.drive_enabled = true;
      break;
    case AsState::Emergency:
    case AsState::Finished:
      out_.ebs = true;  // FS rules: EBS activated in AS Emergency and AS Finished
      out_.max_brake = true;
      break;
  }
  out_.steering_request = held_steering_;
}

void VcuStandin::send_status(Stamp t, const VehicleTruth& truth) {
  status_.stamp = t;
  status_.as_state = state_;
  status_.mission = mission_;
  status_.res_go = res_go_;
  status_.res_emergency = res_emergency_;
  status_.ebs_active = out_.ebs;
  status_.steering_measured = truth.steering + cfg_.steering_noise * unit_noise_(rng_);
  for (std::size_t i = 0; i < 4; ++i)
    status_.wheel_speeds[i] = truth.wheel_speeds[i] + cfg_.wheel_speed_noise * unit_noise_(rng_);
  const std::uint64_t rejected = decoder_.counters().rejected_total();
  status_.faults = emergency_cause_ | (heartbeat_lost(t) ? vcu::kFaultHeartbeatLost : 0u) |
                   (ready_refused_ ? vcu::kFaultReadyRefused : 0u) |
                   (rejected != rx_rejected_reported_ ? vcu::kFaultRxErrors : 0u);
  rx_rejected_reported_ = rejected;
  ++counters_.statuses_sent;
  if (sink_) sink_(t, vcu::encode(status_, seq_.next()));
}

VcuStandinCounters VcuStandin::counters() const {
  VcuStandinCounters c = counters_;
  c.rx = decoder_.counters();
  return c;
}

}  // namespace fsd::sim
