#include "drivers/vlp16/pcap_revolution.hpp"

#include <array>
#include <cmath>
#include <fstream>
#include <optional>

#include "drivers/vlp16/pcap_reader.hpp"
#include "drivers/vlp16/scan_builder.hpp"

namespace fsd {

namespace {

// Azimuth of the first valid return of the capture, if any.
std::optional<double> first_azimuth(const std::filesystem::path& file, const Vlp16Config& config) {
  Vlp16ScanBuilder builder(config, [](Scan&&) {});
  PcapReader reader(file, {static_cast<std::uint16_t>(config.data_port)});
  UdpDatagram d;
  while (reader.next(d)) {
    builder.on_data_packet(d.capture_time, d.payload);
    if (!builder.last_returns().empty()) return builder.last_returns().front().azimuth_deg;
  }
  return std::nullopt;
}

}  // namespace

Vlp16Revolution read_first_revolution(const std::filesystem::path& file, Vlp16Config config) {
  Vlp16Revolution out;
  const auto start = first_azimuth(file, config);
  if (!start) return out;
  config.frame_cut_deg = *start;
  bool have = false;
  Vlp16ScanBuilder builder(config, [&](Scan&& s) {
    if (have) return;
    out.scan = std::move(s);
    have = true;
  });
  PcapReader reader(file, {static_cast<std::uint16_t>(config.data_port)});
  UdpDatagram d;
  while (!have && reader.next(d)) builder.on_data_packet(d.capture_time, d.payload);
  out.complete = have;
  if (!have) builder.flush();  // a capture shorter than a turn: what it has
  out.packets = builder.decode_counters().packets;
  out.rejected_packets = builder.decode_counters().rejected();
  // Span of the azimuth covered, from the start: the largest offset past it among the points.
  double span = 0;
  for (const auto& p : out.scan.points) {
    double rel = rad2deg(p.azimuth) - *start;
    if (rel < 0) rel += 360.0;
    span = std::max(span, rel);
  }
  out.azimuth_span_deg = out.complete ? 360.0 : span;
  return out;
}

bool looks_like_pcap(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::array<unsigned char, 4> m{};
  if (!in.read(reinterpret_cast<char*>(m.data()), 4)) return false;
  const std::uint32_t le = m[0] | (m[1] << 8) | (m[2] << 16) | (static_cast<std::uint32_t>(m[3]) << 24);
  return le == 0xa1b2c3d4u || le == 0xd4c3b2a1u || le == 0xa1b23c4du || le == 0x4d3cb2a1u || le == 0x0a0d0d0au;
}

}  // namespace fsd
