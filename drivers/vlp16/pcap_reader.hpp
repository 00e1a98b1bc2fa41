#pragma once
// Reads the UDP datagrams of a capture file (pcap or pcapng, through libpcap): Ethernet (with VLAN tags),
// Linux cooked capture v1/v2, raw IP and BSD loopback link layers; IPv4 and IPv6. Everything that is not an
// unfragmented UDP datagram is skipped and counted; malformed headers are counted, never trusted.
#include <cstdint>
#include <filesystem>
#include <span>
#include <stdexcept>
#include <vector>

#include "common/time.hpp"

struct pcap;  // libpcap's pcap_t

namespace fsd {

class PcapError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct UdpDatagram {
  Stamp capture_time = 0;  // capture timestamp, s since the Unix epoch (ns resolution when the file has it)
  std::uint16_t src_port = 0, dst_port = 0;
  std::span<const std::uint8_t> payload;  // valid until the next call of next()
};

struct PcapCounters {
  std::uint64_t records = 0;        // capture records read
  std::uint64_t udp = 0;            // UDP datagrams returned (after the port filter)
  std::uint64_t filtered = 0;       // UDP to another port
  std::uint64_t not_udp = 0;        // other protocols, ARP, fragments, unknown link types
  std::uint64_t malformed = 0;      // headers inconsistent with the record length
  std::uint64_t truncated = 0;      // record shorter than the datagram (snap length)
  std::uint64_t bad_ip_length = 0;  // IPv4 total length beyond a complete record; accepted on the UDP length
};

class PcapReader {
 public:
  // Opens the file; `dst_ports` empty = every UDP datagram. Throws PcapError naming the file.
  explicit PcapReader(const std::filesystem::path& file, std::vector<std::uint16_t> dst_ports = {});
  ~PcapReader();
  PcapReader(const PcapReader&) = delete;
  PcapReader& operator=(const PcapReader&) = delete;

  // The next UDP datagram to one of the ports; false at the end of the file. Throws PcapError on a corrupt or
  // truncated file (the datagrams before it have been delivered).
  bool next(UdpDatagram& out);

  const PcapCounters& counters() const { return counters_; }
  int link_type() const { return link_type_; }

 private:
  bool extract(std::span<const std::uint8_t> frame, bool snapped, UdpDatagram& out);
  std::filesystem::path file_;
  std::vector<std::uint16_t> ports_;
  ::pcap* handle_ = nullptr;
  int link_type_ = 0;
  PcapCounters counters_;
};

}  // namespace fsd
