#pragma once
// A pcap file of UDP datagrams as a real VLP-16 puts them on the wire: Ethernet II / IPv4 / UDP from the sensor's
// factory address 192.168.1.201 (MAC in Velodyne's 60:76:88 block) to the broadcast address, source port = the
// destination port (2368 for data, 8308 for position packets). Written with libpcap (pcap_open_dead +
// pcap_dump_open), so tcpdump, Wireshark and our own pcap reader open it. Each record is stamped with the
// simulated time (seconds since the epoch of the run's clock).
#include <cstdint>
#include <span>
#include <string>

#include "common/time.hpp"
#include "common/wire/vlp16_format.hpp"

typedef struct pcap pcap_t;
typedef struct pcap_dumper pcap_dumper_t;

namespace fsd::sim {

class PcapWriter {
 public:
  static constexpr std::size_t kMaxPayload = 65507;  // largest UDP payload in an IPv4 datagram

  // Throws std::runtime_error naming the file when it cannot be created.
  explicit PcapWriter(const std::string& path);
  ~PcapWriter();
  PcapWriter(const PcapWriter&) = delete;
  PcapWriter& operator=(const PcapWriter&) = delete;

  // Throws std::invalid_argument for a payload larger than kMaxPayload or a negative time.
  void write(Stamp t, std::span<const std::uint8_t> udp_payload, std::uint16_t dst_port = wire::vlp16::kDataPort);
  void flush();
  std::uint64_t records() const { return records_; }

 private:
  pcap_t* pcap_ = nullptr;
  pcap_dumper_t* dumper_ = nullptr;
  std::uint64_t records_ = 0;
  std::uint16_t ip_id_ = 0;
};

}  // namespace fsd::sim
