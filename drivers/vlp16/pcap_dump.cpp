#include "drivers/vlp16/pcap_dump.hpp"

#include <cstdio>
#include <sstream>

#include "drivers/vlp16/scan_builder.hpp"

namespace fsd {

PcapDumpSummary dump_vlp16_pcap(const std::filesystem::path& file, const Vlp16Config& config,
                                const std::function<void(const Vlp16Return&)>& on_return) {
  PcapDumpSummary s;
  bool have_points = false;
  Vlp16ScanBuilder builder(config, [&](Scan&& scan) {
    if (!have_points) s.first_firing = scan.points.front().t;
    have_points = true;
    s.last_firing = scan.points.back().t;
  });
  PositionPacketParser positions;
  const auto data_port = static_cast<std::uint16_t>(config.data_port);
  const auto position_port = static_cast<std::uint16_t>(config.position_port);
  PcapReader reader(file, {data_port, position_port});

  UdpDatagram d;
  while (reader.next(d)) {
    if (d.dst_port == data_port) {
      builder.on_data_packet(d.capture_time, d.payload);
      for (const auto& r : builder.last_returns()) on_return(r);
    } else {
      PositionPacket p;
      if (positions.parse(d.payload, p) == PositionStatus::Ok) {
        s.last_pps = p.pps;
        if (p.nmea_state == NmeaState::Valid) s.last_nmea = p.nmea;
      }
    }
  }
  builder.flush();
  s.pcap = reader.counters();
  s.decode = builder.decode_counters();
  s.position = positions.counters();
  s.frames = builder.frames();
  s.lost_packets = builder.lost_packets();
  return s;
}

void append_csv_row(std::string& out, const Vlp16Return& r) {
  char line[160];
  const int n = std::snprintf(line, sizeof line, "%.3f,%u,%.4f,%.3f,%u,%.4f,%.4f,%.4f\n", r.t_us, unsigned{r.laser},
                              r.azimuth_deg, r.distance_m, unsigned{r.intensity}, r.x, r.y, r.z);
  if (n > 0)
    out.append(line, static_cast<std::size_t>(n) < sizeof line ? static_cast<std::size_t>(n) : sizeof line - 1);
}

std::string format_summary(const std::filesystem::path& file, const PcapDumpSummary& s) {
  std::ostringstream o;
  const auto& d = s.decode;
  o << file.string() << "\n"
    << "  data packets:     " << d.packets << " accepted, " << d.rejected() << " rejected (wrong size " << d.wrong_size
    << ", bad flag " << d.bad_flag << ", bad azimuth " << d.bad_azimuth << ", unknown return mode "
    << d.unknown_return_mode << ", unknown product " << d.unknown_product << "), ~" << s.lost_packets << " lost\n"
    << "  points:           " << d.returns << " (no return " << d.no_return << ", out of range " << d.out_of_range
    << ", dual duplicates " << d.dual_duplicates << ")\n"
    << "  frames:           " << s.frames << "\n"
    << "  time span:        " << (s.last_firing - s.first_firing) * 1e3 << " ms\n"
    << "  position packets: " << s.position.packets << " accepted, " << s.position.rejected() << " rejected; PPS "
    << to_string(s.last_pps) << "; NMEA valid " << s.position.nmea_valid << ", absent " << s.position.nmea_absent
    << ", bad checksum " << s.position.nmea_bad_checksum << ", malformed " << s.position.nmea_malformed << "\n";
  if (!s.last_nmea.empty()) o << "  last $GPRMC:      " << s.last_nmea << "\n";
  o << "  capture records:  " << s.pcap.records << " (UDP to other ports " << s.pcap.filtered << ", not UDP "
    << s.pcap.not_udp << ", malformed " << s.pcap.malformed << ", truncated " << s.pcap.truncated
    << ", IPv4 length fixed " << s.pcap.bad_ip_length << ")\n";
  return o.str();
}

}  // namespace fsd
