// The daemon side of the VCU protocol with explicit times: what goes on the wire and when, and when the VCU's
// heartbeat loss is raised.
#include <gtest/gtest.h>

#include <cmath>

#include <nlohmann/json.hpp>

#include "drivers/vcu/vcu_config.hpp"
#include "drivers/vcu/vcu_session.hpp"

namespace fsd {
namespace {

using wire::vcu::AsRequest;
using wire::vcu::Command;

// Plays the VCU: decodes what the session sends with a decoder of its own.
struct FakeVcu {
  std::vector<std::pair<Command, std::uint16_t>> received;
  std::vector<Stamp> times;
  Stamp now = 0;
  wire::vcu::Decoder decoder{{[this](const Command& c, std::uint16_t s) {
                                received.emplace_back(c, s);
                                times.push_back(now);
                              },
                              nullptr, nullptr}};
  VcuSession::Writer writer() {
    return [this](std::vector<std::uint8_t> b) { decoder.feed(b); };
  }
  const Command& last() const { return received.back().first; }
};

struct Events {
  std::vector<VcuLinkEvent> all;
  VcuSession::EventHandler handler() {
    return [this](const VcuLinkEvent& e) { all.push_back(e); };
  }
  int count(VcuLinkEventKind k) const {
    int n = 0;
    for (const auto& e : all) n += e.kind == k;
    return n;
  }
  const VcuLinkEvent* first(VcuLinkEventKind k) const {
    for (const auto& e : all)
      if (e.kind == k) return &e;
    return nullptr;
  }
};

std::vector<std::uint8_t> status_frame(AsState s, std::uint16_t seq, double wheel = 0.0) {
  VcuStatus st;
  st.as_state = s;
  st.mission = Mission::Trackdrive;
  st.wheel_speeds = {wheel, wheel, wheel, wheel};
  return wire::vcu::encode(st, seq);
}

TEST(VcuSession, SendsCommandsAtTheConfiguredRateWithConsecutiveSequence) {
  VcuLinkConfig cfg;
  cfg.rate_hz = 50.0;
  VcuSession session(cfg, 0.0);
  FakeVcu vcu;
  for (int ms = 0; ms <= 1000; ++ms) {
    vcu.now = ms * 1e-3;
    session.tick(vcu.now, vcu.writer());
  }
  // 0, 20, ..., 1000 ms: 51 frames, one every 20 ms.
  ASSERT_EQ(vcu.received.size(), 51u);
  for (std::size_t i = 0; i < vcu.received.size(); ++i) {
    EXPECT_EQ(vcu.received[i].second, i);
    EXPECT_NEAR(vcu.times[i], i * 0.02, 1e-9);
  }
  EXPECT_EQ(vcu.decoder.counters().rejected_total(), 0u);
  EXPECT_EQ(session.counters().commands_sent, 51u);
}

TEST(VcuSession, CommandCarriesTheLatestSlotValues) {
  VcuSession session(VcuLinkConfig{}, 0.0);
  FakeVcu vcu;
  session.set_command({0.0, -0.3, 7.5, false}, 0.0);
  session.set_command({0.0, 0.25, 4.0, false}, 0.001);  // overwrites: only the latest counts
  session.set_as_request(AsRequest::Ready);
  session.set_mission(Mission::Autocross);
  vcu.decoder.feed(session.command_frame(0.002));
  ASSERT_EQ(vcu.received.size(), 1u);
  EXPECT_DOUBLE_EQ(vcu.last().steering, 0.25);
  EXPECT_DOUBLE_EQ(vcu.last().target_speed, 4.0);
  EXPECT_FALSE(vcu.last().brake_hard);
  EXPECT_EQ(vcu.last().as_request, AsRequest::Ready);
  EXPECT_EQ(vcu.last().mission, Mission::Autocross);
  EXPECT_EQ(session.counters().safe_commands_sent, 0u);
}

TEST(VcuSession, SendsASafeCommandBeforeTheFirstControlCommand) {
  VcuSession session(VcuLinkConfig{}, 0.0);
  FakeVcu vcu;
  vcu.decoder.feed(session.command_frame(0.0));
  EXPECT_DOUBLE_EQ(vcu.last().target_speed, 0.0);
  EXPECT_TRUE(vcu.last().brake_hard);
}

TEST(VcuSession, StaleCommandBecomesAControlledStop) {
  VcuLinkConfig cfg;
  cfg.command_timeout = 0.2;
  Events ev;
  VcuSession session(cfg, 0.0, ev.handler());
  FakeVcu vcu;
  session.set_command({0.0, 0.12, 6.0, false}, 1.0);
  vcu.decoder.feed(session.command_frame(1.2));  // exactly at the limit: still fresh
  EXPECT_DOUBLE_EQ(vcu.last().target_speed, 6.0);
  vcu.decoder.feed(session.command_frame(1.21));
  EXPECT_DOUBLE_EQ(vcu.last().target_speed, 0.0);
  EXPECT_TRUE(vcu.last().brake_hard);
  EXPECT_DOUBLE_EQ(vcu.last().steering, 0.12);  // wheel angle held while stopping
  vcu.decoder.feed(session.command_frame(1.3));
  EXPECT_EQ(ev.count(VcuLinkEventKind::CommandStale), 1);  // once per episode
  EXPECT_NEAR(ev.first(VcuLinkEventKind::CommandStale)->t, 1.21, 1e-12);

  session.set_command({0.0, 0.0, 3.0, false}, 1.4);  // the planner is back
  vcu.decoder.feed(session.command_frame(1.41));
  EXPECT_DOUBLE_EQ(vcu.last().target_speed, 3.0);
  EXPECT_EQ(session.counters().safe_commands_sent, 2u);
}

TEST(VcuSession, NonFiniteCommandIsNeverSent) {
  VcuSession session(VcuLinkConfig{}, 0.0);
  FakeVcu vcu;
  session.set_command({0.0, std::nan(""), 5.0, false}, 0.0);
  vcu.decoder.feed(session.command_frame(0.0));
  EXPECT_DOUBLE_EQ(vcu.last().steering, 0.0);
  EXPECT_DOUBLE_EQ(vcu.last().target_speed, 0.0);
  EXPECT_TRUE(vcu.last().brake_hard);
  session.set_command({0.0, 0.1, INFINITY, false}, 0.0);
  vcu.decoder.feed(session.command_frame(0.0));
  EXPECT_DOUBLE_EQ(vcu.last().target_speed, 0.0);
  EXPECT_TRUE(vcu.last().brake_hard);
}

TEST(VcuSession, SafeStopOverridesFreshCommands) {
  VcuSession session(VcuLinkConfig{}, 0.0);
  FakeVcu vcu;
  session.set_as_request(AsRequest::Ready);
  session.set_command({0.0, -0.05, 10.0, false}, 0.0);
  session.enter_safe_stop();
  session.set_command({0.0, -0.05, 10.0, false}, 0.001);
  vcu.decoder.feed(session.command_frame(0.002));
  EXPECT_DOUBLE_EQ(vcu.last().target_speed, 0.0);
  EXPECT_TRUE(vcu.last().brake_hard);
  EXPECT_DOUBLE_EQ(vcu.last().steering, -0.05);
  EXPECT_EQ(vcu.last().as_request, AsRequest::Ready);
}

TEST(VcuSession, DecodesStatusAndStampsItsArrival) {
  VcuSession session(VcuLinkConfig{}, 0.0);
  EXPECT_FALSE(session.status());
  EXPECT_FALSE(session.status_ok());
  session.on_bytes(0.5, status_frame(AsState::Driving, 1, 12.34));
  ASSERT_TRUE(session.status());
  EXPECT_EQ(session.status()->as_state, AsState::Driving);
  EXPECT_EQ(session.status()->mission, Mission::Trackdrive);
  EXPECT_DOUBLE_EQ(session.status()->wheel_speeds[3], 12.34);
  EXPECT_DOUBLE_EQ(session.status()->stamp, 0.5);
  EXPECT_TRUE(session.status_ok());
  session.on_bytes(0.6, status_frame(AsState::Finished, 1));  // replayed: ignored
  EXPECT_EQ(session.status()->as_state, AsState::Driving);
  EXPECT_EQ(session.counters().rx.count(wire::vcu::Reject::Replayed), 1u);
}

// The fault must come within timeout + one command period of the last Status, and not before timeout.
TEST(VcuSession, StatusTimeoutFiresWithinItsBound) {
  for (double rate : {50.0, 100.0, 250.0}) {
    VcuLinkConfig cfg;
    cfg.rate_hz = rate;
    cfg.timeout = 0.1;
    Events ev;
    VcuSession session(cfg, 0.0, ev.handler());
    FakeVcu vcu;
    std::uint16_t seq = 0;
    Stamp last_status = 0;
    Stamp next = 0;
    for (int us = 0; us <= 2'000'000; us += 100) {  // 0.1 ms steps of simulated time
      const Stamp t = us * 1e-6;
      if (t <= 0.7 && us % 10000 == 5000) {  // the VCU sends at 100 Hz until 0.7 s, then goes silent
        session.on_bytes(t, status_frame(AsState::Driving, seq++));
        last_status = t;
      }
      if (t >= next) next = session.tick(t, vcu.writer());
    }
    ASSERT_EQ(ev.count(VcuLinkEventKind::StatusTimeout), 1) << rate;
    const Stamp fired = ev.first(VcuLinkEventKind::StatusTimeout)->t;
    EXPECT_GT(fired - last_status, cfg.timeout) << rate;
    EXPECT_LE(fired - last_status, cfg.timeout + 1.0 / rate + 1e-4) << rate;  // + the 0.1 ms step
    EXPECT_FALSE(session.status_ok());
    EXPECT_EQ(session.counters().status_timeouts, 1u);

    session.on_bytes(2.5, status_frame(AsState::Driving, seq++));
    ASSERT_EQ(ev.count(VcuLinkEventKind::StatusRestored), 1);
    EXPECT_NEAR(ev.first(VcuLinkEventKind::StatusRestored)->gap, 2.5 - last_status, 1e-9);
    EXPECT_TRUE(session.status_ok());
  }
}

TEST(VcuSession, NoStatusAtAllTimesOutFromStart) {
  Events ev;
  VcuSession session(VcuLinkConfig{}, 10.0, ev.handler());
  session.check_timeout(10.1);
  EXPECT_EQ(ev.count(VcuLinkEventKind::StatusTimeout), 0);
  session.check_timeout(10.1001);
  ASSERT_EQ(ev.count(VcuLinkEventKind::StatusTimeout), 1);
  EXPECT_NE(ev.all[0].what.find("since start"), std::string::npos);
}

TEST(VcuSession, StreamResetForgetsSequenceAndCountsThePartialFrame) {
  VcuSession session(VcuLinkConfig{}, 0.0);
  session.on_bytes(0.0, status_frame(AsState::Ready, 500));
  const auto f = status_frame(AsState::Ready, 501);
  session.on_bytes(0.01, std::span(f).first(10));
  session.on_stream_reset();  // the VCU restarted behind a reopened port and counts from 0
  session.on_bytes(0.5, status_frame(AsState::Off, 0));
  EXPECT_EQ(session.status()->as_state, AsState::Off);
  EXPECT_EQ(session.counters().rx.count(wire::vcu::Reject::Truncated), 1u);
  EXPECT_EQ(session.counters().statuses, 2u);
}

TEST(VcuConfig, SectionDeclaresEveryKeyWithTheStructDefaults) {
  ConfigSchema schema;
  vcu_section().describe(schema);
  for (const char* k : {"device", "baud", "rate_hz", "timeout", "command_timeout", "reopen_ms", "stop_frames"})
    EXPECT_NE(schema.find(std::string("drivers.vcu.") + k), nullptr) << k;
  EXPECT_EQ(schema.find("drivers.vcu.rate_hz")->min, 50.0);  // the VCU needs a heartbeat of at least 50 Hz
  auto shared = std::make_shared<ConfigSchema>(schema);
  Config cfg(shared);
  cfg.merge(nlohmann::json::parse(R"({"drivers":{"vcu":{"device":"/dev/pts/7","rate_hz":200}}})"), "test");
  const VcuLinkConfig c = vcu_section().read(cfg);
  EXPECT_EQ(c.device, "/dev/pts/7");
  EXPECT_EQ(c.rate_hz, 200.0);
  EXPECT_EQ(c.timeout, VcuLinkConfig{}.timeout);
  EXPECT_THROW(cfg.set("drivers.vcu.rate_hz", 20.0, "test"), ConfigError);
}

}  // namespace
}  // namespace fsd
