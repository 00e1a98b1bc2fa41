#pragma once
// fsd-daemon's own recording conventions on top of MCAP (the "fsd" profile), what the replayer relies on.
//
// - Header.profile is kProfile; Header.library is "fsd-daemon <version>" (writer.hpp: library_name()).
// - Right after the header, a Metadata record named kRecordingMetadata holds kRecordingVersionKey = the writer's
//   kRecordingVersion (as a decimal string). A replayer refuses a file whose version is larger than its own:
//   recording_version_problem() says so in a sentence.
// - Raw sensor frames (exactly the bytes a device sent, so replay runs the same decoders) are messages with
//   message encoding kRawEncoding on a channel whose schema is named by the frame kind (kRawSchema... below,
//   schema encoding kRawEncoding, the schema data a one-line description of the bytes). log_time is when the
//   frame arrived on the run's clock (ns); publish_time the device's own stamp where it has one, else log_time.
// - Derived channels (state, detections, map, ...) are JSON messages (kJsonEncoding) with a JSON Schema
//   (kJsonSchemaEncoding); the dashboard's Foxglove schemas (web/channel_schemas.cpp) serve as these, so a
//   recording opens in Foxglove Studio.
// - Counters of the recorder (dropped messages per channel, queue high water, ...) go in a Metadata record named
//   kRecorderMetadata, written when the file is closed; `fsd mcap info` prints them.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "common/mcap/records.hpp"

namespace fsd::mcap {

inline constexpr std::string_view kProfile = "fsd";

inline constexpr std::string_view kRecordingMetadata = "fsd.recording";
inline constexpr std::string_view kRecordingVersionKey = "fsd.recording_version";
inline constexpr int kRecordingVersion = 1;
inline constexpr std::string_view kConfigMetadata = "fsd.config";      // the run's configuration, key -> JSON value
inline constexpr std::string_view kRecorderMetadata = "fsd.recorder";  // counters, e.g. "dropped" -> "12"
inline constexpr std::string_view kRunMetadata = "fsd.run";  // how the Stack was built (daemon/recording_format)

inline constexpr std::string_view kRawEncoding = "fsd.raw";
inline constexpr std::string_view kJsonEncoding = "json";
inline constexpr std::string_view kJsonSchemaEncoding = "jsonschema";

// Schema names of the raw frame kinds.
inline constexpr std::string_view kRawSchemaVlp16Data = "fsd.raw.vlp16_data";          // 1206-byte UDP payload
inline constexpr std::string_view kRawSchemaVlp16Position = "fsd.raw.vlp16_position";  // 512-byte UDP payload
inline constexpr std::string_view kRawSchemaNmea = "fsd.raw.nmea";                     // serial bytes as read
inline constexpr std::string_view kRawSchemaJpeg = "fsd.raw.jpeg";                     // one JPEG frame
inline constexpr std::string_view kRawSchemaVcuRx = "fsd.raw.vcu_rx";                  // bytes from the VCU
inline constexpr std::string_view kRawSchemaVcuTx = "fsd.raw.vcu_tx";                  // bytes to the VCU
// The simulator's ground truth, raw frames too (daemon/feeders/truth_frames.hpp).
inline constexpr std::string_view kRawSchemaTruthState = "fsd.raw.truth_state";
inline constexpr std::string_view kRawSchemaTruthCones = "fsd.raw.truth_cones";
inline constexpr std::string_view kRawSchemaTruthScan = "fsd.raw.truth_scan";
inline constexpr std::string_view kRawSchemaTruthLidarReturns = "fsd.raw.truth_lidar_returns";

// The metadata map a writer of this version puts in kRecordingMetadata.
StringMap recording_metadata();

// Empty when a replayer of this version can read a recording with these metadata records; else the sentence to
// refuse it with (a newer recording version, or a version that is not a number). A file without
// kRecordingMetadata (not written by fsd) is accepted: its channels are matched by encoding and schema name.
std::optional<std::string> recording_version_problem(const std::vector<Metadata>& metadata);

}  // namespace fsd::mcap
