#pragma once
// Decoder of VLP-16 data packets (DESIGN.md §6, VLP-16 User Manual ch. 9): validation, single and dual return,
// azimuth interpolation per firing and per laser, firing time of every return, sensor-frame coordinates.
// Pure computation: no I/O, no threads, no allocation beyond the caller's output vector. One owner thread.
#include <array>
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "drivers/vlp16/laser_table.hpp"

namespace fsd {

enum class PacketStatus : std::uint8_t { Ok, WrongSize, BadFlag, BadAzimuth, UnknownReturnMode, UnknownProduct };
std::string_view to_string(PacketStatus s);

// Which echo of a firing a return is. Dual-return packets carry both; when they are the same echo it is emitted
// once as StrongestAndLast.
enum class ReturnKind : std::uint8_t { Strongest, Last, StrongestAndLast };

// One valid return in the sensor frame (x forward, y left, z up; ROS velodyne convention).
struct Vlp16Return {
  // Sensor time of the firing: packet timestamp (µs past the hour, as sent) + firing offset, in µs with the
  // fraction (firing offsets are multiples of 0.001 µs). Not wrapped at the hour: may exceed 3.6e9 in the
  // last packet of an hour.
  double t_us = 0;
  double firing_offset_us = 0;  // from the first firing of the packet
  double azimuth_deg = 0;       // [0, 360), clockwise seen from above, 0 = +x; interpolated per firing
  double distance_m = 0;
  double x = 0, y = 0, z = 0;  // m
  std::uint8_t laser = 0;      // channel 0..15 in the firing sequence
  std::uint8_t intensity = 0;  // calibrated reflectivity 0..255
  std::uint16_t ring = 0;      // 0 = lowest beam
  ReturnKind kind = ReturnKind::Strongest;
};

// The fixed fields of a packet that passed validation.
struct PacketHeader {
  std::uint32_t timestamp_us = 0;  // µs past the hour of the first firing
  std::uint8_t return_mode = 0;    // 0x37, 0x38, 0x39
  std::uint8_t product = 0;        // 0x22 or 0x21
  bool dual() const;
  double duration_us() const;  // time covered by the packet's firings (12 or 6 × 110.592 µs)
};

struct DecodeCounters {
  std::uint64_t packets = 0;  // accepted
  std::uint64_t wrong_size = 0, bad_flag = 0, bad_azimuth = 0, unknown_return_mode = 0, unknown_product = 0;
  std::uint64_t returns = 0;          // emitted
  std::uint64_t no_return = 0;        // distance 0
  std::uint64_t out_of_range = 0;     // outside [min_range, max_range]
  std::uint64_t dual_duplicates = 0;  // strongest == last, emitted once
  std::uint64_t rejected() const { return wrong_size + bad_flag + bad_azimuth + unknown_return_mode + unknown_product; }
};

class PacketDecoder {
 public:
  // Throws std::invalid_argument unless 0 <= min_range < max_range.
  PacketDecoder(LaserTable table, double min_range, double max_range);

  // Checks size, factory bytes, block flags and azimuths; fills `header` when Ok. Does not count.
  static PacketStatus check(std::span<const std::uint8_t> packet, PacketHeader& header);

  // Validates one UDP payload and appends its valid returns to `out` (nothing on rejection). Counts.
  PacketStatus decode(std::span<const std::uint8_t> packet, std::vector<Vlp16Return>& out,
                      PacketHeader* header = nullptr);

  const DecodeCounters& counters() const { return counters_; }
  const LaserTable& lasers() const { return table_; }

 private:
  static constexpr std::size_t kChannels = wire::vlp16::kSequencesPerBlock * wire::vlp16::kLasers;
  void count_rejection(PacketStatus s);
  LaserTable table_;
  std::array<double, kChannels> in_firing_us_{};  // per channel (sequence × 16 + laser)
  std::array<double, kChannels> fraction_{};
  double min_range_, max_range_;
  DecodeCounters counters_;
};

}  // namespace fsd
