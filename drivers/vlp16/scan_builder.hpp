#pragma once
// Data packets in, frames out: decoder + sensor clock + frame assembler, for one VLP-16. The UDP receiver's
// callback, the pcap reader or the virtual car's byte sink feed it; it runs on the caller's thread and keeps
// no lock (one owner thread).
#include <cstdint>
#include <span>
#include <vector>

#include "drivers/vlp16/config.hpp"
#include "drivers/vlp16/decoder.hpp"
#include "drivers/vlp16/frame_assembler.hpp"
#include "drivers/vlp16/sensor_clock.hpp"

namespace fsd {

class Vlp16ScanBuilder {
 public:
  using ScanHandler = FrameAssembler::ScanHandler;

  // Loads the laser table named by the config (throws LaserTableError) and checks the ranges
  // (throws std::invalid_argument).
  Vlp16ScanBuilder(const Vlp16Config& config, ScanHandler on_scan);
  Vlp16ScanBuilder(const Vlp16Config& config, LaserTable table, ScanHandler on_scan);

  // One data packet (UDP payload) received at `receive` on the stack clock: the time the sensor sent it, i.e.
  // just after its last firing (see SensorClock). Rejected packets are counted and otherwise ignored.
  PacketStatus on_data_packet(Stamp receive, std::span<const std::uint8_t> payload);
  // Emits the frame in progress.
  void flush();

  // The valid returns of the last accepted packet (empty after a rejected one), for tools like lidar-dump.
  std::span<const Vlp16Return> last_returns() const { return returns_; }
  const DecodeCounters& decode_counters() const { return decoder_.counters(); }
  std::uint64_t frames() const { return frames_.frames(); }
  std::uint64_t forced_cuts() const { return frames_.forced_cuts(); }
  // Packets missing between consecutive accepted packets, estimated from their sensor timestamps.
  std::uint64_t lost_packets() const { return lost_packets_; }
  const SensorClock& sensor_clock() const { return clock_; }

 private:
  void count_gap(const PacketHeader& h);
  PacketDecoder decoder_;
  SensorClock clock_;
  FrameAssembler frames_;
  ScanHandler on_scan_;
  std::vector<Vlp16Return> returns_;
  bool have_last_ = false;
  PacketHeader last_{};
  std::uint64_t lost_packets_ = 0;
};

}  // namespace fsd
