#pragma once
// The VLP-16 content of a capture file, as `fsd lidar-dump` shows it: every valid return in file order plus a
// summary of packets, points, frames and rejections.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>

#include "drivers/vlp16/config.hpp"
#include "drivers/vlp16/decoder.hpp"
#include "drivers/vlp16/pcap_reader.hpp"
#include "drivers/vlp16/position_packet.hpp"

namespace fsd {

inline constexpr std::string_view kLidarDumpCsvHeader = "t_us,laser,azimuth_deg,distance_m,intensity,x,y,z";

struct PcapDumpSummary {
  PcapCounters pcap;
  DecodeCounters decode;
  PositionCounters position;
  std::uint64_t frames = 0;                 // completed frames plus the partial last one
  std::uint64_t lost_packets = 0;           // estimated from gaps in the sensor timestamps
  Stamp first_firing = 0, last_firing = 0;  // capture-clock times of the first and last return (0 when none)
  PpsState last_pps = PpsState::Absent;
  std::string last_nmea;  // last valid $GPRMC seen
};

// Data packets on config.data_port, position packets on config.position_port; the capture timestamps act as
// receive times. Throws PcapError (missing, unreadable or corrupt file) or LaserTableError.
PcapDumpSummary dump_vlp16_pcap(const std::filesystem::path& file, const Vlp16Config& config,
                                const std::function<void(const Vlp16Return&)>& on_return);

// One CSV row (with '\n') in the columns of kLidarDumpCsvHeader: t_us with 3 decimals (exact), azimuth 4,
// distance 3 (exact), x/y/z 4 (0.1 mm).
void append_csv_row(std::string& out, const Vlp16Return& r);

// Human-readable multi-line summary.
std::string format_summary(const std::filesystem::path& file, const PcapDumpSummary& s);

}  // namespace fsd
