// The VCU stand-in's AS state machine against the Formula Student rules, driven through the wire protocol the
// way the daemon drives it: a stack sends Commands at 100 Hz, the test steps the VCU at 1 kHz in simulated time.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include <nlohmann/json.hpp>

#include "common/wire/vcu_protocol.hpp"
#include "drivers/sim/vcu_standin.hpp"

namespace fsd::sim {
namespace {

using wire::vcu::AsRequest;
using wire::vcu::Command;

class Bench {
 public:
  explicit Bench(VcuStandinConfig cfg = quiet()) {
    vcu = std::make_unique<VcuStandin>(cfg, [this](Stamp ts, std::span<const std::uint8_t> b) {
      status_t.push_back(ts);
      rx.feed(b);
    });
  }
  static VcuStandinConfig quiet() {
    VcuStandinConfig c;
    c.wheel_speed_noise = 0;
    c.steering_noise = 0;
    return c;
  }

  // Steps in 1 ms until `until` (inclusive); the stack sends `cmd` every 10 ms while `stack_alive`.
  void run_until(Stamp until) {
    while (ms_ * 1e-3 <= until + 1e-9) {
      const Stamp t = now();
      if (stack_alive && ms_ % 10 == 0) {
        vcu->feed(t, wire::vcu::encode(cmd, seq.next()));
        last_command_t = t;
      }
      truth.t = t;
      vcu->step(t, truth);
      ++ms_;
    }
  }
  // Runs until the VCU is in `s` or `limit` passes; returns the time it got there (or -1).
  Stamp run_until_state(AsState s, Stamp limit) {
    while (now() <= limit + 1e-9) {
      run_until(now());
      if (vcu->state() == s) return now() - 1e-3;
    }
    return -1;
  }
  Stamp now() const { return ms_ * 1e-3; }
  const ActuatorOutput& out() const { return vcu->output(); }
  const VcuStatus& status() const { return statuses.back(); }

  // Off → Ready with a mission; returns the time Ready was entered.
  Stamp make_ready(Mission m = Mission::Trackdrive) {
    cmd.mission = m;
    cmd.as_request = AsRequest::Ready;
    return run_until_state(AsState::Ready, now() + 0.1);
  }
  // Off → Ready → (5 s) → go → Driving.
  void make_driving() {
    const Stamp ready = make_ready();
    ASSERT_GE(ready, 0);
    run_until(ready + 5.0);
    vcu->press_go(now());
    ASSERT_EQ(vcu->state(), AsState::Driving);
  }

  std::unique_ptr<VcuStandin> vcu;
  std::vector<VcuStatus> statuses;
  std::vector<Stamp> status_t;
  wire::vcu::Decoder rx{{nullptr, [this](const VcuStatus& s, std::uint16_t) { statuses.push_back(s); }, nullptr}};
  wire::vcu::Sequencer seq;
  Command cmd;
  VehicleTruth truth;
  bool stack_alive = true;
  Stamp last_command_t = -1;

 private:
  long ms_ = 0;
};

TEST(VcuStandin, StartsOffAndReportsAtItsRate) {
  Bench b;
  b.stack_alive = false;
  b.run_until(0.999);
  EXPECT_EQ(b.vcu->state(), AsState::Off);
  EXPECT_FALSE(b.out().drive_enabled);
  EXPECT_FALSE(b.out().ebs);
  ASSERT_EQ(b.statuses.size(), 100u);  // 100 Hz over one second, first at t = 0
  EXPECT_NEAR(b.status_t[99] - b.status_t[0], 0.99, 1e-9);
  EXPECT_EQ(b.status().as_state, AsState::Off);
  EXPECT_TRUE(b.status().faults & wire::vcu::kFaultHeartbeatLost);  // nobody talks to it yet
  EXPECT_EQ(b.rx.counters().rejected_total(), 0u);
}

TEST(VcuStandin, GoesReadyWhenTheStackRequestsItWithAMission) {
  Bench b;
  b.cmd.mission = Mission::Acceleration;
  b.run_until(0.5);  // no request yet: the mission is selected, the state stays Off
  EXPECT_EQ(b.vcu->state(), AsState::Off);
  EXPECT_EQ(b.vcu->mission(), Mission::Acceleration);
  const Stamp ready = b.make_ready(Mission::Acceleration);
  EXPECT_NEAR(ready, 0.51, 1e-9);  // at the step that received the next Command
  EXPECT_TRUE(b.out().max_brake);  // service brake engaged in Ready
  EXPECT_FALSE(b.out().drive_enabled);
  b.run_until(b.now() + 0.02);
  EXPECT_EQ(b.status().as_state, AsState::Ready);
  EXPECT_EQ(b.status().mission, Mission::Acceleration);
  EXPECT_EQ(b.status().faults, 0u);
}

TEST(VcuStandin, RefusesReadyWithoutMissionAsmsOrBrakePressure) {
  {
    Bench b;
    EXPECT_LT(b.make_ready(Mission::None), 0);
    EXPECT_EQ(b.vcu->state(), AsState::Off);
    EXPECT_TRUE(b.status().faults & wire::vcu::kFaultReadyRefused);
  }
  for (int which = 0; which < 2; ++which) {
    auto cfg = Bench::quiet();
    (which == 0 ? cfg.asms_on : cfg.brakes_pressurised) = false;
    Bench b(cfg);
    EXPECT_LT(b.make_ready(), 0) << which;
    EXPECT_EQ(b.vcu->state(), AsState::Off);
  }
}

TEST(VcuStandin, NoDrivingBeforeFiveSecondsInReady) {
  Bench b;
  const Stamp ready = b.make_ready();
  b.run_until(ready + 4.99);
  b.vcu->press_go(b.now());
  EXPECT_EQ(b.vcu->state(), AsState::Ready);
  EXPECT_EQ(b.vcu->counters().go_ignored, 1u);
  b.run_until(ready + 5.0);
  b.vcu->press_go(ready + 5.0);
  EXPECT_EQ(b.vcu->state(), AsState::Driving);
  EXPECT_TRUE(b.out().drive_enabled);
  b.run_until(b.now() + 0.02);
  EXPECT_TRUE(b.status().res_go);
  EXPECT_EQ(b.status().as_state, AsState::Driving);
}

TEST(VcuStandin, GoOutsideReadyIsIgnored) {
  Bench b;
  b.vcu->press_go(0.0);
  b.run_until(0.1);
  EXPECT_EQ(b.vcu->state(), AsState::Off);
  EXPECT_EQ(b.vcu->counters().go_ignored, 1u);
}

TEST(VcuStandin, AutomaticGoOfTheSimulatedRes) {
  auto cfg = Bench::quiet();
  cfg.res_go_at_s = 6.0;
  Bench b(cfg);
  const Stamp ready = b.make_ready();
  const Stamp driving = b.run_until_state(AsState::Driving, ready + 10.0);
  EXPECT_NEAR(driving, ready + 6.0, 1.5e-3);

  // An operator pressing too early is ignored like a real early press: the car stays in Ready.
  cfg.res_go_at_s = 2.0;
  Bench early(cfg);
  const Stamp r2 = early.make_ready();
  EXPECT_LT(early.run_until_state(AsState::Driving, r2 + 10.0), 0);
  EXPECT_EQ(early.vcu->state(), AsState::Ready);
  EXPECT_EQ(early.vcu->counters().go_ignored, 1u);
}

TEST(VcuStandin, MotionCommandsAreIgnoredOutsideDriving) {
  Bench b;
  b.cmd.steering = 0.3;
  b.cmd.target_speed = 10.0;
  b.run_until(0.2);  // Off
  EXPECT_EQ(b.out().target_speed, 0.0);
  EXPECT_EQ(b.out().steering_request, 0.0);
  EXPECT_FALSE(b.out().drive_enabled);
  const Stamp ready = b.make_ready();
  b.run_until(ready + 1.0);  // Ready
  EXPECT_EQ(b.out().target_speed, 0.0);
  EXPECT_EQ(b.out().steering_request, 0.0);
  EXPECT_FALSE(b.out().drive_enabled);
  b.run_until(ready + 5.0);
  b.vcu->press_go(b.now());
  b.run_until(b.now() + 0.01);  // Driving: the command goes through (at wire resolution)
  EXPECT_NEAR(b.out().target_speed, 10.0, 1e-9);
  EXPECT_NEAR(b.out().steering_request, 0.3, 1e-9);
  EXPECT_FALSE(b.out().max_brake);
  b.cmd.brake_hard = true;
  b.cmd.target_speed = 0.0;
  b.run_until(b.now() + 0.01);
  EXPECT_TRUE(b.out().max_brake);
  EXPECT_EQ(b.out().target_speed, 0.0);
}

TEST(VcuStandin, FinishedOnlyAtStandstill) {
  Bench b;
  b.make_driving();
  b.truth.vx = 5.0;
  b.cmd.as_request = AsRequest::Finished;
  b.run_until(b.now() + 1.0);
  EXPECT_EQ(b.vcu->state(), AsState::Driving);
  b.truth.vx = 0.01;
  b.run_until(b.now() + 0.01);
  EXPECT_EQ(b.vcu->state(), AsState::Finished);
  EXPECT_TRUE(b.out().ebs);
  EXPECT_FALSE(b.out().drive_enabled);
  // The stack goes quiet after the finish: no emergency in Finished.
  b.stack_alive = false;
  b.run_until(b.now() + 1.0);
  EXPECT_EQ(b.vcu->state(), AsState::Finished);
  EXPECT_EQ(b.status().as_state, AsState::Finished);
  EXPECT_TRUE(b.status().ebs_active);
}

// EBS within heartbeat_timeout + one step of the last Command, and not earlier.
TEST(VcuStandin, HeartbeatLossInReadyOrDrivingFiresTheEbs) {
  for (bool driving : {false, true}) {
    Bench b;
    if (driving) {
      b.make_driving();
      b.truth.vx = 8.0;
    } else {
      b.make_ready();
    }
    b.run_until(b.now() + 0.5);
    b.stack_alive = false;
    const Stamp last = b.last_command_t;
    const Stamp t_emergency = b.run_until_state(AsState::Emergency, last + 1.0);
    ASSERT_GE(t_emergency, 0) << driving;
    EXPECT_GT(t_emergency - last, 0.1) << driving;
    EXPECT_LE(t_emergency - last, 0.1 + 1e-3 + 1e-9) << driving;
    EXPECT_TRUE(b.out().ebs);
    EXPECT_FALSE(b.out().drive_enabled);
    EXPECT_EQ(b.out().target_speed, 0.0);
    b.run_until(b.now() + 0.02);
    EXPECT_EQ(b.status().as_state, AsState::Emergency);
    EXPECT_TRUE(b.status().ebs_active);
    EXPECT_TRUE(b.status().faults & wire::vcu::kFaultHeartbeatLost);
    EXPECT_TRUE(b.status().faults & wire::vcu::kFaultEmergencyHeartbeat);
  }
}

TEST(VcuStandin, HeartbeatLossInOffIsNoEmergency) {
  Bench b;
  b.run_until(0.5);
  b.stack_alive = false;
  b.run_until(2.0);
  EXPECT_EQ(b.vcu->state(), AsState::Off);
  EXPECT_FALSE(b.out().ebs);
}

TEST(VcuStandin, ResEmergencyFromEveryState) {
  for (AsState from : {AsState::Off, AsState::Ready, AsState::Driving, AsState::Finished}) {
    Bench b;
    if (from == AsState::Ready) b.make_ready();
    if (from == AsState::Driving || from == AsState::Finished) b.make_driving();
    if (from == AsState::Finished) {
      b.cmd.as_request = AsRequest::Finished;
      b.run_until(b.now() + 0.02);
    }
    ASSERT_EQ(b.vcu->state(), from);
    b.vcu->press_emergency(b.now());
    EXPECT_EQ(b.vcu->state(), AsState::Emergency) << to_string(from);
    EXPECT_TRUE(b.out().ebs);
    EXPECT_FALSE(b.out().drive_enabled);
    b.run_until(b.now() + 0.02);
    EXPECT_TRUE(b.status().res_emergency);
    EXPECT_TRUE(b.status().faults & wire::vcu::kFaultEmergencyRes);
    EXPECT_EQ(b.vcu->transitions().back().from, from);
  }
}

TEST(VcuStandin, StackEmergencyRequestFromEveryState) {
  for (AsState from : {AsState::Off, AsState::Ready, AsState::Driving}) {
    Bench b;
    if (from == AsState::Ready) b.make_ready();
    if (from == AsState::Driving) b.make_driving();
    b.cmd.as_request = AsRequest::Emergency;
    const Stamp sent = b.now();
    EXPECT_GE(b.run_until_state(AsState::Emergency, sent + 0.05), 0) << to_string(from);
    EXPECT_LE(b.now() - sent, 0.011);  // within the next Command's step
    b.run_until(b.now() + 0.02);
    EXPECT_TRUE(b.status().faults & wire::vcu::kFaultEmergencyRequest);
  }
}

TEST(VcuStandin, EmergencyIsLatched) {
  Bench b;
  b.make_driving();
  b.vcu->press_emergency(b.now());
  // Everything that could pull it out: heartbeat back, Ready requested again, RES go, motion commands.
  b.cmd.as_request = AsRequest::Ready;
  b.cmd.target_speed = 5.0;
  b.run_until(b.now() + 6.0);
  b.vcu->press_go(b.now());
  b.run_until(b.now() + 1.0);
  EXPECT_EQ(b.vcu->state(), AsState::Emergency);
  EXPECT_TRUE(b.out().ebs);
  EXPECT_FALSE(b.out().drive_enabled);
  EXPECT_EQ(b.out().target_speed, 0.0);
  // Only the operator's ASMS off releases it, to Off; a new run can then start from scratch.
  b.vcu->set_asms(b.now(), false);
  EXPECT_EQ(b.vcu->state(), AsState::Off);
  EXPECT_FALSE(b.out().ebs);
  b.run_until(b.now() + 0.02);
  EXPECT_FALSE(b.status().res_emergency);
  EXPECT_EQ(b.status().faults & wire::vcu::kFaultEmergencyRes, 0u);
  EXPECT_EQ(b.vcu->state(), AsState::Off);  // ASMS still off: Ready refused
  b.vcu->set_asms(b.now(), true);
  EXPECT_GE(b.run_until_state(AsState::Ready, b.now() + 0.1), 0);
}

TEST(VcuStandin, AsmsOffWhileDrivingIsAnEmergency) {
  Bench b;
  b.make_driving();
  b.vcu->set_asms(b.now(), false);
  EXPECT_EQ(b.vcu->state(), AsState::Emergency);
  b.run_until(b.now() + 0.02);
  EXPECT_TRUE(b.status().faults & wire::vcu::kFaultEmergencyAsms);
}

TEST(VcuStandin, ReportsTruthWheelSpeedsAndSteeringAtWireResolution) {
  Bench b;
  b.truth.wheel_speeds = {10.123, 10.456, -0.004, 3.0};
  b.truth.steering = -0.12345;
  b.run_until(0.05);
  const auto& s = b.status();
  for (std::size_t i = 0; i < 4; ++i) EXPECT_NEAR(s.wheel_speeds[i], b.truth.wheel_speeds[i], 0.005 + 1e-12);
  EXPECT_NEAR(s.steering_measured, -0.12345, 0.00005 + 1e-12);
}

TEST(VcuStandin, MeasurementNoiseHasTheConfiguredSpread) {
  VcuStandinConfig cfg;
  cfg.wheel_speed_noise = 0.05;
  cfg.steering_noise = 0.002;
  Bench b(cfg);
  b.truth.wheel_speeds = {5, 5, 5, 5};
  b.truth.steering = 0.1;
  b.run_until(20.0);  // 2000 Status frames
  double sum = 0, sq = 0, ssum = 0, ssq = 0;
  for (const auto& s : b.statuses) {
    const double e = s.wheel_speeds[0] - 5.0, es = s.steering_measured - 0.1;
    sum += e, sq += e * e, ssum += es, ssq += es * es;
  }
  const double n = static_cast<double>(b.statuses.size());
  EXPECT_NEAR(sum / n, 0.0, 0.005);
  EXPECT_NEAR(std::sqrt(sq / n), 0.05, 0.005);
  EXPECT_NEAR(ssum / n, 0.0, 0.0002);
  EXPECT_NEAR(std::sqrt(ssq / n), 0.002, 0.0002);
}

TEST(VcuStandin, SameSeedSameBytes) {
  auto run = [](int seed) {
    VcuStandinConfig cfg;
    cfg.seed = seed;
    std::vector<std::uint8_t> bytes;
    VcuStandin v(cfg, [&](Stamp, std::span<const std::uint8_t> b) { bytes.insert(bytes.end(), b.begin(), b.end()); });
    VehicleTruth truth;
    truth.wheel_speeds = {3, 3, 3, 3};
    for (int ms = 0; ms < 500; ++ms) v.step(ms * 1e-3, truth);
    return bytes;
  };
  EXPECT_EQ(run(7), run(7));
  EXPECT_NE(run(7), run(8));
}

TEST(VcuStandin, BadInputIsCountedAndReported) {
  Bench b;
  b.make_ready();
  const std::vector<std::uint8_t> junk = {0xa5, 0x5a, 0x08, 0x01, 0x01, 0, 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 9, 0xff};
  b.vcu->feed(b.now(), junk);
  b.run_until(b.now() + 0.02);
  EXPECT_EQ(b.vcu->state(), AsState::Ready);
  EXPECT_GE(b.vcu->counters().rx.rejected_total(), 1u);
  bool reported = false;
  for (const auto& s : b.statuses) reported |= (s.faults & wire::vcu::kFaultRxErrors) != 0;
  EXPECT_TRUE(reported);
  EXPECT_FALSE(b.status().faults & wire::vcu::kFaultRxErrors);  // only in the Status right after
}

TEST(VcuStandin, ConfigSection) {
  ConfigSchema schema;
  vcu_standin_section().describe(schema);
  for (const char* k : {"status_rate_hz", "heartbeat_timeout", "ready_to_drive_s", "res_go_at_s", "asms_on",
                        "brakes_pressurised", "standstill_speed", "wheel_speed_noise", "steering_noise", "seed"})
    EXPECT_NE(schema.find(std::string("sim.vcu.") + k), nullptr) << k;
  Config cfg(std::make_shared<ConfigSchema>(schema));
  cfg.merge(nlohmann::json::parse(R"({"sim":{"vcu":{"res_go_at_s":5.5}}})"), "test");
  const auto c = vcu_standin_section().read(cfg);
  EXPECT_EQ(c.res_go_at_s, 5.5);
  EXPECT_EQ(c.ready_to_drive_s, 5.0);
  EXPECT_EQ(c.heartbeat_timeout, 0.1);
}

}  // namespace
}  // namespace fsd::sim
