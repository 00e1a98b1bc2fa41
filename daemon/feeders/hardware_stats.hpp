#pragma once
// Counters of every driver of `fsd run` on the car, read at one moment: the periodic log line (rates over the
// period and the error totals) and the report's "drivers" object are made from two of these.
#include <cstdint>
#include <optional>
#include <string>

#include <nlohmann/json_fwd.hpp>

#include "common/time.hpp"
#include "drivers/camera/camera_source.hpp"
#include "drivers/gnss/gnss_driver.hpp"
#include "drivers/serial/serial_port.hpp"
#include "drivers/vcu/vcu_link.hpp"
#include "drivers/vlp16/decoder.hpp"
#include "drivers/vlp16/position_packet.hpp"
#include "drivers/vlp16/udp_receiver.hpp"

namespace fsd {

struct LidarCounters {
  UdpReceiverCounters udp;
  DecodeCounters decode;
  std::uint64_t scans = 0;
  std::uint64_t lost_packets = 0;  // gaps in the sensor's packet timestamps
  // Position packets (drivers.vlp16.position_port): the sensor's clock, PPS lock and the GPS sentence it got.
  UdpReceiverCounters position_udp;
  PositionCounters position;
  PpsState pps = PpsState::Absent;  // in the newest accepted position packet
};

struct GnssLinkCounters {
  GnssCounters nmea;
  SerialCounters port;
};

struct HardwareCounters {
  Stamp t = 0;  // when they were read, on the run's clock
  LidarCounters lidar;
  GnssLinkCounters gnss;
  VcuLinkCounters vcu;
  std::optional<CameraStats> camera;  // nullopt: no camera configured
  std::uint64_t control_cycles = 0;
  std::uint64_t control_overruns = 0;  // cycles that started a whole period late
  std::uint64_t frames_dropped = 0;    // raw frames the control thread's queue had to drop (it fell behind)
};

// One line: per-driver rates between `before` and `now`, then the error counters' totals since the start.
std::string rates_line(const HardwareCounters& before, const HardwareCounters& now);
// Totals, for the report.
nlohmann::json counters_json(const HardwareCounters& c);

}  // namespace fsd
