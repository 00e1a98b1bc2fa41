#pragma once
// The first full revolution of a VLP-16 capture as one Scan, for `fsd detect` on a pcap: the frame starts at the
// azimuth of the first valid return and ends when the head comes back to it, so a capture of about one turn
// (like ../shared/data/vlp16/velodyne_vlp16.pcap) still yields a whole sweep; a shorter capture yields what it has.
#include <filesystem>

#include "common/types.hpp"
#include "drivers/vlp16/config.hpp"

namespace fsd {

struct Vlp16Revolution {
  Scan scan;                    // sensor frame, capture-clock times
  bool complete = false;        // the head came back to the start azimuth
  double azimuth_span_deg = 0;  // azimuth covered
  std::uint64_t packets = 0, rejected_packets = 0;
};

// Throws PcapError (missing, unreadable or corrupt file) or LaserTableError.
Vlp16Revolution read_first_revolution(const std::filesystem::path& file, Vlp16Config config);

// Whether the file starts like a pcap or pcapng capture (magic number), to tell it from a CSV cloud.
bool looks_like_pcap(const std::filesystem::path& file);

}  // namespace fsd
