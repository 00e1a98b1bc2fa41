#pragma once
// The daemon's VCU link on a serial port (DESIGN.md §4, §6, §7): the transport of a VcuSession that its owner
// (the daemon's Stack) holds. A sender thread writes a Command at `rate_hz` from the session's latest
// ControlCommand and AS request (the control thread only fills the session's slot) and watches the VCU's
// heartbeat; the port's I/O thread hands the received bytes to on_rx_bytes, and the owner feeds them to the
// session on its own thread (so that a recording sees them in the order the stack used them). On stop() safe
// Commands (speed 0, brake) go out before the port closes. The sender paces itself in wall time because the VCU is
// a real-time device; lockstep runs use VcuSession directly.
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
    VcuSession::EventHandler on_event;  // the port's faults and recoveries; called from the port's thread
    // The bytes received from the VCU, to be handed to the session's on_bytes (and to a recorder). Required.
    std::function<void(Stamp, std::span<const std::uint8_t>)> on_rx_bytes;
    std::function<void(Stamp, std::span<const std::uint8_t>)> on_tx_bytes;  // raw output, for the recorder
  };

  // The session must outlive the link. Throws std::invalid_argument without on_rx_bytes.
  VcuLink(const VcuLinkConfig& cfg, VcuSession& session, const Clock& clock, Handlers h);
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

  std::optional<VcuStatus> status() const { return session_.status(); }  // as decoded by the owner
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
  VcuSession& session_;
  SerialPort port_;
  std::mutex m_;
  std::condition_variable cv_;
  bool stop_requested_ = false;
  std::thread sender_;
};

}  // namespace fsd
