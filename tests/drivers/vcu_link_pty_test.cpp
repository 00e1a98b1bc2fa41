// End to end over a pseudo-terminal: the daemon's VcuLink on the slave path, the virtual car's VcuStandin on the
// master end, as in `fsd run --sim`. Then the device is pulled and plugged back: the link recovers by itself,
// reports the gap, and the VCU has meanwhile fired its EBS on the lost heartbeat. Waits are bounded polls.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <mutex>
#include <thread>

#include "common/clock.hpp"
#include "drivers/serial/pseudo_terminal.hpp"
#include "drivers/sim/vcu_standin.hpp"
#include "drivers/vcu/vcu_link.hpp"
#include "tests/scratch_dir.hpp"
#include "tests/wait_until.hpp"

namespace fsd {
namespace {

namespace fs = std::filesystem;
using wire::vcu::AsRequest;

using test::wait_until;

// The virtual car's side: a thread that moves bytes between the pty master and the VCU stand-in and steps it
// every millisecond. It also keeps the Commands it received, to check what the daemon said last.
class Car {
 public:
  Car(const Clock& clock, sim::VcuStandinConfig cfg)
      : clock_(clock), vcu_(cfg, [this](Stamp, std::span<const std::uint8_t> b) {
          if (pty_) pty_->write(b);
        }) {}
  ~Car() { stop(); }

  void plug(std::unique_ptr<PseudoTerminal> pty) {
    std::lock_guard l(m_);
    pty_ = std::move(pty);
  }
  void unplug() {
    std::lock_guard l(m_);
    pty_.reset();
  }
  void start() {
    thread_ = std::thread([this] {
      std::vector<std::uint8_t> buf(1024);
      while (running_) {
        {
          std::lock_guard l(m_);
          const Stamp t = clock_.now();
          if (pty_) {
            while (const auto n = pty_->read(buf, 0.0)) {
              const auto bytes = std::span(buf).first(n);
              vcu_.feed(t, bytes);
              tap_.feed(bytes);
            }
          }
          vcu_.step(t, truth_);
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
      }
    });
  }
  void stop() {
    running_ = false;
    if (thread_.joinable()) thread_.join();
  }
  template <class F>
  auto with(F f) {
    std::lock_guard l(m_);
    return f(vcu_);
  }
  std::vector<wire::vcu::Command> commands() {
    std::lock_guard l(m_);
    return commands_;
  }

 private:
  const Clock& clock_;
  std::mutex m_;
  std::unique_ptr<PseudoTerminal> pty_;
  sim::VcuStandin vcu_;
  std::vector<wire::vcu::Command> commands_;
  wire::vcu::Decoder tap_{
      {[this](const wire::vcu::Command& c, std::uint16_t) { commands_.push_back(c); }, nullptr, nullptr}};
  sim::VehicleTruth truth_;
  std::atomic<bool> running_{true};
  std::thread thread_;
};

struct EventLog {
  std::mutex m;
  std::vector<VcuLinkEvent> all;
  void add(const VcuLinkEvent& e) {
    std::lock_guard l(m);
    all.push_back(e);
  }
  std::optional<VcuLinkEvent> first(VcuLinkEventKind k) {
    std::lock_guard l(m);
    for (const auto& e : all)
      if (e.kind == k) return e;
    return std::nullopt;
  }
};

TEST(VcuLinkOverPty, DrivesTheStandinAndRecoversFromAPulledDevice) {
  RealClock clock;
  sim::VcuStandinConfig vcfg;
  vcfg.ready_to_drive_s = 0.3;  // short for the test; the 5 s rule is tested in tests/sim
  vcfg.res_go_at_s = 0.3;
  Car car(clock, vcfg);
  const fs::path dev = test::scratch_path("ttyVCU");
  fs::remove(dev);
  auto pty = std::make_unique<PseudoTerminal>();
  fs::create_symlink(pty->slave_path(), dev);
  car.plug(std::move(pty));
  car.start();

  VcuLinkConfig cfg;
  cfg.device = dev.string();
  cfg.rate_hz = 100;
  cfg.timeout = 0.1;
  cfg.command_timeout = 0.5;
  cfg.reopen_ms = 20;
  EventLog events;
  std::atomic<std::uint64_t> rx_bytes{0}, tx_bytes{0};
  // The session is the stack's; the link is its transport and hands it every received byte.
  VcuSession session(cfg, clock.now(), [&](const VcuLinkEvent& e) { events.add(e); });
  VcuLink link(cfg, session, clock,
               {[&](const VcuLinkEvent& e) { events.add(e); },
                [&](Stamp t, std::span<const std::uint8_t> b) {
                  rx_bytes += b.size();
                  session.on_bytes(t, b);
                },
                [&](Stamp, std::span<const std::uint8_t> b) { tx_bytes += b.size(); }});
  link.set_mission(Mission::Trackdrive);
  link.set_as_request(AsRequest::Ready);
  link.start();

  // The control thread: keeps the slot fresh.
  std::atomic<bool> control_on{true};
  std::thread control([&] {
    while (control_on) {
      link.set_command({clock.now(), 0.1, 3.0, false});
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
  });
  auto link_state = [&] {
    const auto s = link.status();
    return s ? s->as_state : AsState::Off;
  };

  // Off → Ready on the link's request, → Driving on the simulated RES; the command reaches the actuators.
  ASSERT_TRUE(wait_until([&] { return link_state() == AsState::Driving; }));
  EXPECT_EQ(link.status()->mission, Mission::Trackdrive);
  EXPECT_TRUE(link.status()->res_go);
  ASSERT_TRUE(wait_until([&] { return car.with([](auto& v) { return v.output().target_speed; }) == 3.0; }));
  EXPECT_NEAR(car.with([](auto& v) { return v.output().steering_request; }), 0.1, 1e-9);
  EXPECT_TRUE(link.status_ok());
  EXPECT_GT(rx_bytes.load(), 0u);
  EXPECT_GT(tx_bytes.load(), 0u);

  // Pull the device.
  car.unplug();
  fs::remove(dev);
  ASSERT_TRUE(wait_until([&] { return events.first(VcuLinkEventKind::PortLost).has_value(); }));
  ASSERT_TRUE(wait_until([&] { return events.first(VcuLinkEventKind::StatusTimeout).has_value(); }));
  // The VCU lost our heartbeat and braked.
  ASSERT_TRUE(wait_until([&] { return car.with([](auto& v) { return v.state(); }) == AsState::Emergency; }));
  EXPECT_TRUE(car.with([](auto& v) { return v.output().ebs; }));
  std::this_thread::sleep_for(std::chrono::milliseconds(100));  // stay unplugged across several reopen attempts

  // Plug it back in: a new pty behind the same path.
  pty = std::make_unique<PseudoTerminal>();
  fs::create_symlink(pty->slave_path(), dev);
  car.plug(std::move(pty));
  ASSERT_TRUE(wait_until([&] { return events.first(VcuLinkEventKind::PortRestored).has_value(); }));
  ASSERT_TRUE(wait_until([&] { return events.first(VcuLinkEventKind::StatusRestored).has_value(); }));
  const auto lost = *events.first(VcuLinkEventKind::PortLost);
  const auto back = *events.first(VcuLinkEventKind::PortRestored);
  EXPECT_GE(back.gap, 0.1);
  EXPECT_NEAR(back.t - lost.t, back.gap, 1e-6);
  EXPECT_TRUE(link.status_ok());
  ASSERT_TRUE(wait_until([&] { return link_state() == AsState::Emergency; }));  // latched on the VCU
  EXPECT_TRUE(link.status()->ebs_active);
  EXPECT_TRUE(link.status()->faults & wire::vcu::kFaultEmergencyHeartbeat);
  const auto c = link.counters();
  EXPECT_EQ(c.port.gaps, 1u);
  EXPECT_GE(c.port.opens, 2u);
  EXPECT_EQ(c.session.status_timeouts, 1u);

  // Shutdown: the last Commands the VCU hears are a controlled stop.
  control_on = false;
  control.join();
  link.stop();
  // Commands written before stop() may still be on their way: wait for the stop frames themselves (the link
  // sends cfg.stop_frames of them) to be the last ones heard, not for any three more.
  auto ends_in_stops = [&] {
    const auto cmds = car.commands();
    if (cmds.size() < 3) return false;
    for (std::size_t i = cmds.size() - 3; i < cmds.size(); ++i)
      if (!cmds[i].brake_hard) return false;
    return true;
  };
  ASSERT_GE(cfg.stop_frames, 3);
  EXPECT_TRUE(wait_until(ends_in_stops, 1.0));
  const auto cmds = car.commands();
  ASSERT_GE(cmds.size(), 3u);
  for (std::size_t i = cmds.size() - 3; i < cmds.size(); ++i) {
    EXPECT_EQ(cmds[i].target_speed, 0.0);
    EXPECT_TRUE(cmds[i].brake_hard);
    EXPECT_NEAR(cmds[i].steering, 0.1, 1e-9);
  }
  EXPECT_EQ(car.with([](auto& v) { return v.counters().rx.rejected_total(); }), 0u);
  car.stop();
  fs::remove(dev);
}

}  // namespace
}  // namespace fsd
