#pragma once
// The daemon's side of the VCU protocol without threads or I/O: the latest ControlCommand and AS request in a
// slot, Command frames encoded from them (safe ones when the command is stale or on shutdown), Status frames
// decoded, and the VCU's heartbeat watched. VcuLink drives it from a serial port and a sender thread; lockstep
// runs drive it directly with the simulated VCU (tick() and on_bytes() with explicit times).
#include <cstdint>
#include <functional>
#include <mutex>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "common/types.hpp"
#include "common/wire/vcu_protocol.hpp"
#include "drivers/vcu/vcu_config.hpp"

namespace fsd {

enum class VcuLinkEventKind : std::uint8_t {
  StatusTimeout,   // no valid Status for longer than `timeout` (fault)
  StatusRestored,  // Status frames again after a timeout; `gap` is the time without them
  CommandStale,    // the control thread's command is older than `command_timeout`: safe commands are sent
  PortLost,        // the serial device failed or disappeared
  PortRestored,    // the serial device is back; `gap` is the outage
};
std::string_view to_string(VcuLinkEventKind k);

struct VcuLinkEvent {
  VcuLinkEventKind kind;
  Stamp t = 0;
  Duration gap = 0;
  std::string what;
};
// "kind: what" (or the kind alone), as fault logs and reports show an event.
std::string describe(const VcuLinkEvent& e);

struct VcuSessionCounters {
  std::uint64_t commands_sent = 0;
  std::uint64_t safe_commands_sent = 0;  // of those: no fresh command, or shutting down
  std::uint64_t statuses = 0;
  std::uint64_t status_timeouts = 0;
  wire::vcu::DecoderCounters rx;
};

class VcuSession {
 public:
  using Writer = std::function<void(std::vector<std::uint8_t>)>;
  using EventHandler = std::function<void(const VcuLinkEvent&)>;

  // `start` begins the wait for the first Status. Events are delivered outside the session's lock.
  VcuSession(const VcuLinkConfig& cfg, Stamp start, EventHandler on_event = {});

  // Latest-value slots, cheap and never blocking on I/O (called from the control thread).
  void set_command(const ControlCommand& c, Stamp now);
  void set_as_request(wire::vcu::AsRequest r);
  void set_mission(Mission m);
  // From now on every Command is safe: target speed 0 with brake request, steering held.
  void enter_safe_stop();

  // Encodes the Command for `now` (safe if the slot is stale, empty or stopping), next sequence number.
  std::vector<std::uint8_t> command_frame(Stamp now);
  // Raises StatusTimeout once when the last Status is older than `timeout`.
  void check_timeout(Stamp now);
  // For callers stepping time themselves: sends a Command when one is due at `rate_hz`, checks the timeout,
  // and returns when the next Command is due.
  Stamp tick(Stamp now, const Writer& write);

  void on_bytes(Stamp now, std::span<const std::uint8_t> bytes);
  // The byte stream was interrupted (port closed or reopened).
  void on_stream_reset();

  std::optional<VcuStatus> status() const;  // stamped with its arrival time
  bool status_ok() const;                   // a Status arrived and no timeout since
  VcuSessionCounters counters() const;
  const VcuLinkConfig& config() const { return cfg_; }

 private:
  void emit(std::vector<VcuLinkEvent>& out);

  VcuLinkConfig cfg_;
  EventHandler on_event_;
  mutable std::mutex m_;
  // Guarded by m_:
  std::optional<ControlCommand> command_;
  Stamp command_at_ = 0;
  bool command_stale_ = false;
  wire::vcu::AsRequest request_ = wire::vcu::AsRequest::None;
  Mission mission_ = Mission::None;
  bool stopping_ = false;
  wire::vcu::Sequencer seq_;
  wire::vcu::Decoder decoder_;
  std::optional<VcuStatus> status_;
  Stamp last_status_at_;
  Stamp rx_now_ = 0;  // time of the bytes being decoded
  bool timed_out_ = false;
  wire::vcu::SendSchedule schedule_;
  VcuSessionCounters counters_;
  std::vector<VcuLinkEvent> pending_;  // raised while decoding, emitted after the lock is released
};

}  // namespace fsd
