#include "drivers/sim/sensors/pcap_writer.hpp"

#include <pcap/pcap.h>

#include <array>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace fsd::sim {

namespace {
constexpr std::size_t kEthernetHeader = 14, kIpHeader = 20, kUdpHeader = 8;
constexpr std::size_t kHeaders = kEthernetHeader + kIpHeader + kUdpHeader;
constexpr std::array<std::uint8_t, 6> kBroadcastMac{0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF};
constexpr std::array<std::uint8_t, 6> kSensorMac{0x60, 0x76, 0x88, 0x00, 0x00, 0x01};
constexpr std::array<std::uint8_t, 4> kSensorIp{192, 168, 1, 201};
constexpr std::array<std::uint8_t, 4> kBroadcastIp{255, 255, 255, 255};

void put_be16(std::uint8_t* p, std::uint16_t v) {
  p[0] = static_cast<std::uint8_t>(v >> 8);
  p[1] = static_cast<std::uint8_t>(v & 0xFF);
}

std::uint16_t ipv4_checksum(const std::uint8_t* header) {
  std::uint32_t sum = 0;
  for (std::size_t i = 0; i < kIpHeader; i += 2) sum += static_cast<std::uint32_t>(header[i] << 8 | header[i + 1]);
  while (sum >> 16) sum = (sum & 0xFFFF) + (sum >> 16);
  return static_cast<std::uint16_t>(~sum);
}
}  // namespace

PcapWriter::PcapWriter(const std::string& path) {
  pcap_ = pcap_open_dead(DLT_EN10MB, 65535);
  if (!pcap_) throw std::runtime_error(path + ": cannot create a pcap handle");
  dumper_ = pcap_dump_open(pcap_, path.c_str());
  if (!dumper_) {
    const std::string why = pcap_geterr(pcap_);
    pcap_close(pcap_);
    throw std::runtime_error(path + ": cannot write pcap file: " + why);
  }
}

PcapWriter::~PcapWriter() {
  if (dumper_) pcap_dump_close(dumper_);
  if (pcap_) pcap_close(pcap_);
}

void PcapWriter::write(Stamp t, std::span<const std::uint8_t> payload, std::uint16_t dst_port) {
  if (payload.size() > kMaxPayload)
    throw std::invalid_argument("UDP payload of " + std::to_string(payload.size()) + " bytes does not fit a datagram");
  if (!(t >= 0.0)) throw std::invalid_argument("pcap records need a time at or after the epoch");
  std::vector<std::uint8_t> frame(kHeaders + payload.size());
  std::uint8_t* eth = frame.data();
  std::copy(kBroadcastMac.begin(), kBroadcastMac.end(), eth);
  std::copy(kSensorMac.begin(), kSensorMac.end(), eth + 6);
  put_be16(eth + 12, 0x0800);  // IPv4

  std::uint8_t* ip = eth + kEthernetHeader;
  ip[0] = 0x45;  // version 4, 5 words
  ip[1] = 0;
  put_be16(ip + 2, static_cast<std::uint16_t>(kIpHeader + kUdpHeader + payload.size()));
  put_be16(ip + 4, ip_id_++);
  put_be16(ip + 6, 0x4000);  // don't fragment
  ip[8] = 255;               // TTL
  ip[9] = 17;                // UDP
  std::copy(kSensorIp.begin(), kSensorIp.end(), ip + 12);
  std::copy(kBroadcastIp.begin(), kBroadcastIp.end(), ip + 16);
  put_be16(ip + 10, ipv4_checksum(ip));

  std::uint8_t* udp = ip + kIpHeader;
  put_be16(udp, dst_port);  // the sensor sends from the port it sends to
  put_be16(udp + 2, dst_port);
  put_be16(udp + 4, static_cast<std::uint16_t>(kUdpHeader + payload.size()));
  put_be16(udp + 6, 0);  // no checksum (allowed over IPv4), as the sensor does
  std::copy(payload.begin(), payload.end(), udp + kUdpHeader);

  pcap_pkthdr hdr{};
  const double whole = std::floor(t);
  hdr.ts.tv_sec = static_cast<decltype(hdr.ts.tv_sec)>(whole);
  hdr.ts.tv_usec = static_cast<decltype(hdr.ts.tv_usec)>(std::min(999999.0, std::round((t - whole) * 1e6)));
  hdr.caplen = hdr.len = static_cast<bpf_u_int32>(frame.size());
  pcap_dump(reinterpret_cast<u_char*>(dumper_), &hdr, frame.data());
  ++records_;
}

void PcapWriter::flush() { pcap_dump_flush(dumper_); }

}  // namespace fsd::sim
