#pragma once
// The VCU link protocol (docs/vcu-protocol.md): one codec used by the daemon's VcuLink and by the virtual car's
// VCU firmware stand-in. Frame, little-endian:
//
//   0  u8   sync 0xA5        3  u8   version (1)          5  u16  sequence counter (per sender, wraps)
//   1  u8   sync 0x5A        4  u8   message type         7  N    payload
//   2  u8   payload length N (≤ kMaxPayload)              7+N u16 CRC-16/CCITT-FALSE over bytes 2 .. 6+N
//
// The codec does no I/O: encoders return bytes, the streaming Decoder takes bytes in any chunking and calls a
// handler per valid frame, rejecting and counting everything else.
#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "common/types.hpp"

namespace fsd::wire::vcu {

inline constexpr std::uint8_t kSync0 = 0xA5, kSync1 = 0x5A;
inline constexpr std::uint8_t kVersion = 1;
inline constexpr std::size_t kHeaderSize = 7;
inline constexpr std::size_t kCrcSize = 2;
inline constexpr std::size_t kMaxPayload = 64;
inline constexpr std::size_t kMaxFrameSize = kHeaderSize + kMaxPayload + kCrcSize;

enum class MessageType : std::uint8_t { Command = 0x01, Status = 0x81 };
inline constexpr std::size_t kCommandPayloadSize = 8;
inline constexpr std::size_t kStatusPayloadSize = 18;
inline constexpr std::size_t kCommandFrameSize = kHeaderSize + kCommandPayloadSize + kCrcSize;
inline constexpr std::size_t kStatusFrameSize = kHeaderSize + kStatusPayloadSize + kCrcSize;

// Scaled integers on the wire.
inline constexpr double kAngleUnit = 1e-4;  // rad per count, i16: ±3.2767 rad
inline constexpr double kSpeedUnit = 0.01;  // m/s per count; target speed u16 (0..655.35), wheel speeds i16

// What the stack asks of the VCU's AS state machine. A level, repeated in every Command: the VCU acts on it when
// its own conditions hold (e.g. Ready needs a selected mission; Finished needs standstill).
enum class AsRequest : std::uint8_t { None = 0, Ready = 1, Finished = 2, Emergency = 3 };
std::string_view to_string(AsRequest r);

// Command flags (byte 4 of the Command payload).
inline constexpr std::uint8_t kCmdBrakeHard = 0x01;
// Status flags (byte 2 of the Status payload).
inline constexpr std::uint8_t kStatusResGo = 0x01;
inline constexpr std::uint8_t kStatusResEmergency = 0x02;
inline constexpr std::uint8_t kStatusEbsActive = 0x04;

// VcuStatus::faults bits (u32 on the wire).
inline constexpr std::uint32_t kFaultHeartbeatLost = 1u << 0;       // no valid Command within the VCU's timeout now
inline constexpr std::uint32_t kFaultEmergencyHeartbeat = 1u << 1;  // Emergency entered by heartbeat loss
inline constexpr std::uint32_t kFaultEmergencyRes = 1u << 2;        // Emergency entered by the RES
inline constexpr std::uint32_t kFaultEmergencyRequest = 1u << 3;    // Emergency entered on the stack's request
inline constexpr std::uint32_t kFaultEmergencyAsms = 1u << 4;       // Emergency entered by ASMS off while Driving
inline constexpr std::uint32_t kFaultReadyRefused = 1u << 5;        // Ready requested but its conditions do not hold
inline constexpr std::uint32_t kFaultRxErrors = 1u << 6;            // the VCU rejected frames since its last Status

// Daemon → VCU, sent at ≥ 50 Hz; every valid Command is also the heartbeat.
struct Command {
  double steering = 0;      // front wheel angle, rad, left positive
  double target_speed = 0;  // m/s
  bool brake_hard = false;  // maximum service braking
  AsRequest as_request = AsRequest::None;
  Mission mission = Mission::None;
};
Command make_command(const ControlCommand& c, AsRequest request, Mission mission);

// VCU → daemon is VcuStatus (common/types.hpp); its stamp is not on the wire (the receiver stamps arrival).

// Encoders. Values outside the wire range saturate; NaN encodes as 0. `seq` is the sender's counter.
std::vector<std::uint8_t> encode(const Command& c, std::uint16_t seq);
std::vector<std::uint8_t> encode(const VcuStatus& s, std::uint16_t seq);
// A frame of any type/version/payload (tests, fuzz seeds). Throws std::invalid_argument on payload > kMaxPayload.
std::vector<std::uint8_t> encode_frame(MessageType type, std::uint16_t seq, std::span<const std::uint8_t> payload,
                                       std::uint8_t version = kVersion);

// CRC-16/CCITT-FALSE (poly 0x1021, init 0xFFFF, no reflection, xorout 0); check value of "123456789" is 0x29B1.
std::uint16_t crc16(std::span<const std::uint8_t> bytes);

// One sender's sequence counter.
class Sequencer {
 public:
  explicit Sequencer(std::uint16_t first = 0) : next_(first) {}
  std::uint16_t next() { return next_++; }
  std::uint16_t peek() const { return next_; }

 private:
  std::uint16_t next_;
};

// When the next periodic frame is due (both ends send at a fixed rate): a grid origin + n·period, so rounding
// never accumulates; a caller that falls behind continues on the grid instead of sending a burst.
class SendSchedule {
 public:
  SendSchedule(double rate_hz, Stamp origin) : period_(1.0 / rate_hz), origin_(origin) {}
  // True when a frame is due at `now` (then the schedule moves on).
  bool due(Stamp now);
  Stamp next() const { return origin_ + static_cast<double>(n_) * period_; }
  Duration period() const { return period_; }

 private:
  Duration period_;
  Stamp origin_;
  std::uint64_t n_ = 0;
};

enum class Reject : std::uint8_t {
  BadCrc,       // CRC mismatch (line noise, or a false sync in garbage)
  Truncated,    // a frame cut short: the next sync arrived inside it, or the stream was reset mid-frame
  BadVersion,   // valid CRC, unknown protocol version
  Oversized,    // length field above kMaxPayload
  UnknownType,  // valid CRC, message type not known (or not expected by this receiver)
  BadPayload,   // length wrong for the type, or a field out of range (enum value, reserved bits)
  Replayed,     // same sequence number as the last accepted frame
  OutOfOrder,   // sequence number older than the last accepted one (serial-number arithmetic, wraps)
};
inline constexpr std::size_t kRejectKinds = 8;
std::string_view to_string(Reject r);

struct DecoderCounters {
  std::uint64_t frames = 0;         // accepted
  std::uint64_t garbage_bytes = 0;  // bytes skipped while hunting for a sync
  std::uint64_t lost = 0;           // frames missing between accepted sequence numbers
  std::uint64_t restarts = 0;       // sender restarts accepted (see DecoderConfig::restart_after)
  std::array<std::uint64_t, kRejectKinds> rejected{};
  std::uint64_t rejected_total() const;
  std::uint64_t count(Reject r) const { return rejected[static_cast<std::size_t>(r)]; }
};

struct DecoderConfig {
  // After this many consecutive out-of-order frames that are in order among themselves the sender is taken to
  // have restarted its counter (VCU reset) and the decoder follows it. 0 disables.
  int restart_after = 5;
};

// Streaming decoder for one direction: feed() any chunking of the byte stream; valid frames reach the handlers
// in order, everything else is rejected and counted. Never throws on input.
class Decoder {
 public:
  struct Handlers {
    std::function<void(const Command&, std::uint16_t seq)> on_command;   // null: Commands rejected UnknownType
    std::function<void(const VcuStatus&, std::uint16_t seq)> on_status;  // null: Status rejected UnknownType
    std::function<void(Reject, std::uint16_t seq)> on_reject;            // optional, for logging
  };
  explicit Decoder(Handlers h, DecoderConfig cfg = {});

  void feed(std::span<const std::uint8_t> bytes);
  // The stream was interrupted (port closed/reopened): a partial frame is counted Truncated and the sequence
  // tracking restarts with the next frame.
  void reset();
  const DecoderCounters& counters() const { return counters_; }
  std::size_t buffered() const { return buf_.size(); }

 private:
  void parse();
  // Returns the bytes consumed from the front of buf_, 0 when more input is needed.
  std::size_t try_frame();
  void reject(Reject r, std::uint16_t seq);
  bool accept_sequence(std::uint16_t seq);

  Handlers h_;
  DecoderConfig cfg_;
  std::vector<std::uint8_t> buf_;
  DecoderCounters counters_;
  std::optional<std::uint16_t> last_seq_;
  std::optional<std::uint16_t> last_old_seq_;  // last out-of-order frame, to recognise a restart
  int old_run_ = 0;
};

}  // namespace fsd::wire::vcu
