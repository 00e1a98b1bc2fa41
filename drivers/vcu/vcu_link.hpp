#pragma once
// The daemon's VCU link on a serial port (DESIGN.md §4, §6, §7): a sender thread writes a Command at `rate_hz`
// from the latest ControlCommand and AS request (the control thread only fills a slot), the port's I/O thread
// decodes Status frames, the VCU's heartbeat is watched, and on stop() safe Commands (speed 0, brake) go out
// before the port closes. The sender paces itself in wall time because the VCU is a real-time device; lockstep
// runs use VcuSession directly.
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <span>
#include <thread>

#include "drivers/serial/serial_port.hpp"
#include "drivers/vcu/vcu_session.hpp"

namespace fsd {

class Clock;

struct VcuLinkCounters {
  VcuSessionCounters session;
  SerialCounters port;
};

class VcuLink {
 public:
  struct Handlers {
    VcuSession::EventHandler on_event;  // faults and recoveries; called from the link's threads
    std::function<void(Stamp, std::span<const std::uint8_t>)> on_rx_bytes;  // raw input, for the recorder
    std::function<void(Stamp, std::span<const std::uint8_t>)> on_tx_bytes;  // raw output, for the recorder
  };

  VcuLink(const VcuLinkConfig& cfg, const Clock& clock, Handlers h = {});
  ~VcuLink();
  VcuLink(const VcuLink&) = delete;
  VcuLink& operator=(const VcuLink&) = delete;

  void start();  // once: after stop() the link only ever sends safe Commands
  // Sends `stop_frames` safe Commands at the command rate, then closes the port. Idempotent.
  void stop();

  // Never block on I/O.
  void set_command(const ControlCommand& c);
  void set_as_request(wire::vcu::AsRequest r) { session_.set_as_request(r); }
  void set_mission(Mission m) { session_.set_mission(m); }

  std::optional<VcuStatus> status() const { return session_.status(); }
  bool status_ok() const { return session_.status_ok(); }
  bool port_open() const { return port_.is_open(); }
  VcuLinkCounters counters() const { return {session_.counters(), port_.counters()}; }
  const VcuLinkConfig& config() const { return cfg_; }

 private:
  void send_one();
  void run_sender();
  void event(const VcuLinkEvent& e);

  VcuLinkConfig cfg_;
  const Clock& clock_;
  Handlers h_;
  VcuSession session_;
  SerialPort port_;
  std::mutex m_;
  std::condition_variable cv_;
  bool stop_requested_ = false;
  std::thread sender_;
};

}  // namespace fsd
