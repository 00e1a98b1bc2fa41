#pragma once
// What `fsd run --record` puts in an MCAP file on top of the fsd profile (common/mcap/fsd_profile.hpp), and what
// `fsd run --replay` reads back: the topics, the two binary messages of the Stack's own, the run's metadata.
//
//   /raw/<channel>   every raw frame the Stack took (RawChannel names: /raw/vlp16_data, /raw/nmea, /raw/camera,
//                    /raw/vcu_rx, /raw/vcu_tx, /raw/truth_state, ...): the bytes exactly, log_time = receive time (ns)
//   /stack/cycle     one per Stack::step(now): u8 version (1), f64 now, u32 n, n x f64 the exact receive times of the
//                    n frames written since the previous marker (a double does not survive a trip through
//                    nanoseconds, and replay must feed the very same times to be bit for bit)
//   /stack/command   one per step, at its end: u8 version (1), f64 now, f64 command stamp, f64 steering (rad),
//                    f64 target speed (m/s), u8 brake_hard, u8 AS request (common/wire/vcu_protocol.hpp)
// Metadata: fsd.recording (the version), fsd.config (every configuration key the Stack was built from, key ->
// JSON value), fsd.run (RecordedRun below). Attachment track.csv in simulator runs (the layout driven).
// All little-endian. Decoding checks every length (recordings are untrusted input).
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "common/mcap/records.hpp"
#include "common/types.hpp"
#include "common/wire/vcu_protocol.hpp"
#include "daemon/stack/raw_frame.hpp"

namespace fsd {

inline constexpr std::string_view kCycleTopic = "/stack/cycle";
inline constexpr std::string_view kCommandTopic = "/stack/command";
inline constexpr std::string_view kCycleSchema = "fsd.stack.cycle";
inline constexpr std::string_view kCommandSchema = "fsd.stack.command";
inline constexpr std::string_view kTrackAttachment = "track.csv";
// Simulator runs, in the last part at its close: {"json": the live scorecard's "injected_faults"} (the virtual car's
// fault windows and the truth around them: measured live, carried to the replay's scorecard).
inline constexpr std::string_view kInjectedFaultsMetadata = "fsd.injected_faults";
inline constexpr std::uint32_t kMaxCycleFrames = 1u << 20;  // frames between two cycles a decoder accepts

std::string raw_topic(RawChannel c);  // "/raw/vlp16_data"
std::optional<RawChannel> raw_channel_of_topic(std::string_view topic);
std::string_view raw_schema(RawChannel c);         // fsd_profile's schema names
std::string raw_schema_description(RawChannel c);  // the schema data: a line about the bytes

// Seconds on the run's clock to MCAP nanoseconds (negative times clamp to 0).
mcap::Timestamp to_ns(Stamp t);

struct CycleMarker {
  Stamp now = 0;
  std::vector<Stamp> frame_times;  // of the frames since the previous marker, in order
};
std::vector<std::uint8_t> encode_cycle(const CycleMarker& m);
std::optional<CycleMarker> decode_cycle(std::span<const std::uint8_t> bytes);

struct CommandRecord {
  Stamp now = 0;
  ControlCommand command;
  wire::vcu::AsRequest request = wire::vcu::AsRequest::None;
};
std::vector<std::uint8_t> encode_command(const CommandRecord& c);
std::optional<CommandRecord> decode_command(std::span<const std::uint8_t> bytes);

// How the live feeder built the Stack (StackOptions), so that replay builds the same one.
struct RecordedRun {
  std::string mode = "sim";  // "sim" (fsd run --sim) or "car"
  bool lockstep = false;     // headless sim: the lap-2 build ran inside the step (replays bit for bit)
  Mission mission = Mission::Trackdrive;
  int laps = 2;
  bool simulator = false;
  Stamp start = 0;
  std::optional<double> camera_latency;  // StackOptions::camera was set
  std::string camera_calibration;        // its calibration (JSON text), when set
};
mcap::StringMap to_metadata(const RecordedRun& r);
// Throws std::invalid_argument naming the key for a missing or malformed value.
RecordedRun recorded_run_from_metadata(const mcap::StringMap& m);

// The configuration (nested, Config::as_json) as flat key -> JSON text, what fsd.config holds.
mcap::StringMap flatten_config(const nlohmann::json& nested);

}  // namespace fsd
