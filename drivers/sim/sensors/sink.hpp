#pragma once
// Where the virtual car's sensors put their bytes. A sensor model produces exactly what the real device sends
// (a UDP payload, a serial byte stream) stamped with the simulated time it leaves the device; the wiring decides
// the transport: loopback UDP or a pseudo-terminal in real-time runs, a direct hand-over to the driver's decoder
// in lockstep runs, a pcap file for `fsd sim --lidar-pcap`.
#include <cstdint>
#include <functional>
#include <span>

#include "common/time.hpp"

namespace fsd::sim {

using ByteSink = std::function<void(Stamp t, std::span<const std::uint8_t> bytes)>;

}  // namespace fsd::sim
