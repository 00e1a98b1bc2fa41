#include "drivers/vlp16/pcap_reader.hpp"

#include <algorithm>
#include <optional>
#include <string>

#include <pcap/pcap.h>

namespace fsd {

namespace {

constexpr std::uint16_t kEtherIPv4 = 0x0800, kEtherIPv6 = 0x86DD, kEtherVlan = 0x8100, kEtherQinQ = 0x88A8;
constexpr std::uint8_t kProtoUdp = 17;

std::uint16_t be16(std::span<const std::uint8_t> b, std::size_t at) {
  return static_cast<std::uint16_t>((b[at] << 8) | b[at + 1]);
}

// The network-layer packet of a link-layer frame and its ethertype.
struct NetworkPacket {
  std::uint16_t ethertype;
  std::span<const std::uint8_t> bytes;
};

// Link layers without an ethertype: the IP version nibble tells.
NetworkPacket by_ip_version(std::span<const std::uint8_t> ip) {
  return {!ip.empty() && (ip[0] >> 4) == 6 ? kEtherIPv6 : kEtherIPv4, ip};
}

}  // namespace

PcapReader::PcapReader(const std::filesystem::path& file, std::vector<std::uint16_t> dst_ports)
    : file_(file), ports_(std::move(dst_ports)) {
  char err[PCAP_ERRBUF_SIZE] = {};
  if (!std::filesystem::exists(file)) throw PcapError("pcap file '" + file.string() + "': no such file");
  handle_ = pcap_open_offline_with_tstamp_precision(file.c_str(), PCAP_TSTAMP_PRECISION_NANO, err);
  if (!handle_) throw PcapError("pcap file '" + file.string() + "': " + err);
  link_type_ = pcap_datalink(handle_);
}

PcapReader::~PcapReader() {
  if (handle_) pcap_close(handle_);
}

bool PcapReader::next(UdpDatagram& out) {
  for (;;) {
    pcap_pkthdr* hdr = nullptr;
    const u_char* data = nullptr;
    const int rc = pcap_next_ex(handle_, &hdr, &data);
    if (rc == PCAP_ERROR_BREAK) return false;
    if (rc != 1) throw PcapError("pcap file '" + file_.string() + "': " + pcap_geterr(handle_));
    ++counters_.records;
    out.capture_time = static_cast<double>(hdr->ts.tv_sec) + static_cast<double>(hdr->ts.tv_usec) * 1e-9;
    if (!extract({data, hdr->caplen}, hdr->caplen < hdr->len, out)) continue;
    if (!ports_.empty() && std::find(ports_.begin(), ports_.end(), out.dst_port) == ports_.end()) {
      ++counters_.filtered;
      continue;
    }
    ++counters_.udp;
    return true;
  }
}

// Walks link → network → UDP headers, checking every length against the bytes present.
bool PcapReader::extract(std::span<const std::uint8_t> f, bool snapped, UdpDatagram& out) {
  const auto fail = [&](std::uint64_t& counter) {
    ++counter;
    return false;
  };
  std::optional<NetworkPacket> net;
  switch (link_type_) {
    case DLT_EN10MB: {
      std::size_t at = 12;
      if (f.size() < at + 2) return fail(counters_.malformed);
      std::uint16_t type = be16(f, at);
      for (int tags = 0; (type == kEtherVlan || type == kEtherQinQ) && tags < 2; ++tags) {
        at += 4;
        if (f.size() < at + 2) return fail(counters_.malformed);
        type = be16(f, at);
      }
      net = NetworkPacket{type, f.subspan(at + 2)};
      break;
    }
    case DLT_LINUX_SLL:
      if (f.size() < 16) return fail(counters_.malformed);
      net = NetworkPacket{be16(f, 14), f.subspan(16)};
      break;
    case DLT_LINUX_SLL2:
      if (f.size() < 20) return fail(counters_.malformed);
      net = NetworkPacket{be16(f, 0), f.subspan(20)};
      break;
    case DLT_RAW:
    case DLT_IPV4:
    case DLT_IPV6:
      net = by_ip_version(f);
      break;
    case DLT_NULL:
    case DLT_LOOP:
      // A 4-byte address family whose byte order and values differ between systems: skip it.
      if (f.size() < 4) return fail(counters_.malformed);
      net = by_ip_version(f.subspan(4));
      break;
    default:
      return fail(counters_.not_udp);
  }

  auto ip = net->bytes;
  std::span<const std::uint8_t> udp;
  if (net->ethertype == kEtherIPv4) {
    if (ip.size() < 20 || (ip[0] >> 4) != 4) return fail(counters_.malformed);
    const std::size_t ihl = static_cast<std::size_t>(ip[0] & 0x0F) * 4;
    const std::size_t total = be16(ip, 2);
    if (ihl < 20 || total < ihl) return fail(counters_.malformed);
    if (ip[9] != kProtoUdp) return fail(counters_.not_udp);
    const bool fragment = (be16(ip, 6) & 0x3FFF) != 0;  // more-fragments flag or a fragment offset
    if (fragment) return fail(counters_.not_udp);
    std::size_t end = total;  // Ethernet padding may follow the packet: its total length rules
    if (ip.size() < total) {
      if (snapped) return fail(counters_.truncated);
      // The whole frame was captured yet the header claims more: VLP-16 position packets carry the data
      // packets' total length (1234). The UDP length below still has to fit the bytes present.
      ++counters_.bad_ip_length;
      end = ip.size();
    }
    if (end < ihl) return fail(counters_.malformed);
    udp = ip.subspan(ihl, end - ihl);
  } else if (net->ethertype == kEtherIPv6) {
    if (ip.size() < 40 || (ip[0] >> 4) != 6) return fail(counters_.malformed);
    if (ip[6] != kProtoUdp) return fail(counters_.not_udp);  // extension headers are not followed
    const std::size_t payload_len = be16(ip, 4);
    if (ip.size() < 40 + payload_len) return fail(snapped ? counters_.truncated : counters_.malformed);
    udp = ip.subspan(40, payload_len);
  } else {
    return fail(counters_.not_udp);
  }

  if (udp.size() < 8) return fail(counters_.malformed);
  const std::size_t udp_len = be16(udp, 4);
  if (udp_len < 8 || udp_len > udp.size()) return fail(counters_.malformed);
  out.src_port = be16(udp, 0);
  out.dst_port = be16(udp, 2);
  out.payload = udp.subspan(8, udp_len - 8);
  return true;
}

}  // namespace fsd
