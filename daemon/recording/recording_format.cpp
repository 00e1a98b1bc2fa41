#include "daemon/recording/recording_format.hpp"

#include <bit>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "common/mcap/fsd_profile.hpp"

namespace fsd {

namespace {

constexpr std::uint8_t kVersion = 1;
constexpr std::size_t kCommandSize = 1 + 4 * 8 + 2;

void put_u8(std::vector<std::uint8_t>& b, std::uint8_t v) { b.push_back(v); }
void put_u32(std::vector<std::uint8_t>& b, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) b.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
}
void put_f64(std::vector<std::uint8_t>& b, double v) {
  const auto u = std::bit_cast<std::uint64_t>(v);
  for (int i = 0; i < 8; ++i) b.push_back(static_cast<std::uint8_t>(u >> (8 * i)));
}

// Reads little-endian fields from a span; every read checks what remains.
struct Cursor {
  std::span<const std::uint8_t> b;
  std::size_t at = 0;
  bool ok = true;
  bool need(std::size_t n) {
    ok = ok && b.size() - at >= n;
    return ok;
  }
  std::uint8_t u8() { return need(1) ? b[at++] : 0; }
  std::uint32_t u32() {
    if (!need(4)) return 0;
    std::uint32_t v = 0;
    for (int i = 0; i < 4; ++i) v |= static_cast<std::uint32_t>(b[at++]) << (8 * i);
    return v;
  }
  double f64() {
    if (!need(8)) return 0;
    std::uint64_t v = 0;
    for (int i = 0; i < 8; ++i) v |= static_cast<std::uint64_t>(b[at++]) << (8 * i);
    return std::bit_cast<double>(v);
  }
};

void flatten(const nlohmann::json& j, const std::string& prefix, mcap::StringMap& out) {
  if (j.is_object() && !j.empty()) {
    for (const auto& [k, v] : j.items()) flatten(v, prefix.empty() ? k : prefix + "." + k, out);
    return;
  }
  if (!prefix.empty()) out[prefix] = j.dump();
}

const std::string& required(const mcap::StringMap& m, const std::string& key) {
  const auto it = m.find(key);
  if (it == m.end()) throw std::invalid_argument(std::string(mcap::kRunMetadata) + ": no '" + key + "'");
  return it->second;
}

double number(const mcap::StringMap& m, const std::string& key) {
  const std::string& v = required(m, key);
  try {
    std::size_t used = 0;
    const double d = std::stod(v, &used);
    if (used == v.size() && std::isfinite(d)) return d;
  } catch (const std::exception&) {}
  throw std::invalid_argument(std::string(mcap::kRunMetadata) + ": '" + key + "' is not a number: '" + v + "'");
}

std::string exact(double v) {
  nlohmann::json j = v;  // the shortest text that reads back to the same double
  return j.dump();
}

}  // namespace

std::string raw_topic(RawChannel c) { return "/raw/" + std::string(to_string(c)); }

std::optional<RawChannel> raw_channel_of_topic(std::string_view topic) {
  constexpr std::string_view prefix = "/raw/";
  if (topic.substr(0, prefix.size()) != prefix) return std::nullopt;
  return raw_channel_from_string(topic.substr(prefix.size()));
}

std::string_view raw_schema(RawChannel c) {
  switch (c) {
    case RawChannel::Vlp16Data:
      return mcap::kRawSchemaVlp16Data;
    case RawChannel::Vlp16Position:
      return mcap::kRawSchemaVlp16Position;
    case RawChannel::Nmea:
      return mcap::kRawSchemaNmea;
    case RawChannel::Camera:
      return mcap::kRawSchemaJpeg;
    case RawChannel::VcuRx:
      return mcap::kRawSchemaVcuRx;
    case RawChannel::VcuTx:
      return mcap::kRawSchemaVcuTx;
    case RawChannel::TruthState:
      return mcap::kRawSchemaTruthState;
    case RawChannel::TruthCones:
      return mcap::kRawSchemaTruthCones;
    case RawChannel::TruthScan:
      return mcap::kRawSchemaTruthScan;
    case RawChannel::TruthLidarReturns:
      return mcap::kRawSchemaTruthLidarReturns;
  }
  return "fsd.raw.unknown";
}

std::string raw_schema_description(RawChannel c) {
  switch (c) {
    case RawChannel::Vlp16Data:
      return "VLP-16 data packet: the 1206-byte UDP payload (port 2368)";
    case RawChannel::Vlp16Position:
      return "VLP-16 position packet: the 512-byte UDP payload (port 8308)";
    case RawChannel::Nmea:
      return "GNSS-INS serial bytes (NMEA 0183) as read, any chunking";
    case RawChannel::Camera:
      return "one camera frame, JPEG";
    case RawChannel::VcuRx:
      return "VCU protocol bytes from the VCU (docs/vcu-protocol.md)";
    case RawChannel::VcuTx:
      return "VCU protocol bytes to the VCU (docs/vcu-protocol.md)";
    case RawChannel::TruthState:
      return "simulator truth: the true vehicle state (daemon/feeders/truth_frames.hpp)";
    case RawChannel::TruthCones:
      return "simulator truth: the standing cones (daemon/feeders/truth_frames.hpp)";
    case RawChannel::TruthScan:
      return "simulator truth: the ideal detector's scan tick (no bytes)";
    case RawChannel::TruthLidarReturns:
      return "simulator truth: the LiDAR returns from each cone (daemon/feeders/truth_frames.hpp)";
  }
  return "";
}

mcap::Timestamp to_ns(Stamp t) {
  if (!(t > 0)) return 0;
  if (t >= 1.8e10) return static_cast<mcap::Timestamp>(1.8e19);
  return static_cast<mcap::Timestamp>(std::llround(t * 1e9));
}

std::vector<std::uint8_t> encode_cycle(const CycleMarker& m) {
  std::vector<std::uint8_t> b;
  b.reserve(1 + 8 + 4 + 8 * m.frame_times.size());
  put_u8(b, kVersion);
  put_f64(b, m.now);
  put_u32(b, static_cast<std::uint32_t>(m.frame_times.size()));
  for (const Stamp t : m.frame_times) put_f64(b, t);
  return b;
}

std::optional<CycleMarker> decode_cycle(std::span<const std::uint8_t> bytes) {
  Cursor c{bytes};
  if (c.u8() != kVersion) return std::nullopt;
  CycleMarker m;
  m.now = c.f64();
  const std::uint32_t n = c.u32();
  if (!c.ok || n > kMaxCycleFrames || bytes.size() - c.at != std::size_t{n} * 8) return std::nullopt;
  m.frame_times.resize(n);
  for (auto& t : m.frame_times) t = c.f64();
  if (!std::isfinite(m.now)) return std::nullopt;
  return m;
}

std::vector<std::uint8_t> encode_command(const CommandRecord& r) {
  std::vector<std::uint8_t> b;
  b.reserve(kCommandSize);
  put_u8(b, kVersion);
  put_f64(b, r.now);
  put_f64(b, r.command.stamp);
  put_f64(b, r.command.steering);
  put_f64(b, r.command.target_speed);
  put_u8(b, r.command.brake_hard ? 1 : 0);
  put_u8(b, static_cast<std::uint8_t>(r.request));
  return b;
}

std::optional<CommandRecord> decode_command(std::span<const std::uint8_t> bytes) {
  if (bytes.size() != kCommandSize) return std::nullopt;
  Cursor c{bytes};
  if (c.u8() != kVersion) return std::nullopt;
  CommandRecord r;
  r.now = c.f64();
  r.command.stamp = c.f64();
  r.command.steering = c.f64();
  r.command.target_speed = c.f64();
  const std::uint8_t brake = c.u8(), request = c.u8();
  if (brake > 1 || request > 3) return std::nullopt;
  r.command.brake_hard = brake == 1;
  r.request = static_cast<wire::vcu::AsRequest>(request);
  return r;
}

mcap::StringMap to_metadata(const RecordedRun& r) {
  mcap::StringMap m;
  m["mode"] = r.mode;
  m["lockstep"] = r.lockstep ? "true" : "false";
  m["mission"] = std::string(to_string(r.mission));
  m["laps"] = std::to_string(r.laps);
  m["simulator"] = r.simulator ? "true" : "false";
  m["start"] = exact(r.start);
  if (r.camera_latency) {
    m["camera_latency"] = exact(*r.camera_latency);
    m["camera_calibration"] = r.camera_calibration;
  }
  return m;
}

RecordedRun recorded_run_from_metadata(const mcap::StringMap& m) {
  RecordedRun r;
  r.mode = required(m, "mode");
  if (r.mode != "sim" && r.mode != "car")
    throw std::invalid_argument(std::string(mcap::kRunMetadata) + ": unknown mode '" + r.mode + "'");
  r.lockstep = required(m, "lockstep") == "true";
  const auto mission = mission_from_string(required(m, "mission"));
  if (!mission)
    throw std::invalid_argument(std::string(mcap::kRunMetadata) + ": unknown mission '" + m.at("mission") + "'");
  r.mission = *mission;
  const double laps = number(m, "laps");
  if (laps < 1 || laps > 1000 || laps != std::floor(laps))
    throw std::invalid_argument(std::string(mcap::kRunMetadata) + ": 'laps' out of range");
  r.laps = static_cast<int>(laps);
  r.simulator = required(m, "simulator") == "true";
  r.start = number(m, "start");
  if (m.count("camera_latency")) {
    r.camera_latency = number(m, "camera_latency");
    r.camera_calibration = required(m, "camera_calibration");
  }
  return r;
}

mcap::StringMap flatten_config(const nlohmann::json& nested) {
  mcap::StringMap out;
  flatten(nested, "", out);
  return out;
}

}  // namespace fsd
