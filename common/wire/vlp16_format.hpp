#pragma once
// The Velodyne VLP-16 data packet (VLP-16 User Manual, ch. 9), shared by the driver that decodes it and the
// virtual car that emits it. Only layout and constants live here; decoding logic is in drivers/vlp16.
//
// UDP payload, 1206 bytes, little-endian:
//   12 × data block (100 bytes): flag 0xFFEE (bytes FF EE), azimuth u16 in 0.01°, 32 × (distance u16 in 2 mm,
//                                reflectivity u8) = two firing sequences of 16 lasers
//   timestamp u32: µs past the top of the hour of the first firing of the packet
//   factory u8 ×2: return mode (0x37 strongest, 0x38 last, 0x39 dual), product id (0x22 VLP-16; 0x21 early fw)
// Position packet: 512 bytes on port 8308 with the GPS timestamp and an NMEA $GPRMC sentence.
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

namespace fsd::wire::vlp16 {

inline constexpr std::size_t kPacketSize = 1206;
inline constexpr std::size_t kBlocks = 12;
inline constexpr std::size_t kBlockSize = 100;
inline constexpr std::size_t kLasers = 16;
inline constexpr std::size_t kSequencesPerBlock = 2;
inline constexpr std::size_t kTimestampOffset = 1200;
inline constexpr std::size_t kReturnModeOffset = 1204;
inline constexpr std::size_t kProductOffset = 1205;
inline constexpr std::uint8_t kFlag0 = 0xFF, kFlag1 = 0xEE;

inline constexpr std::uint8_t kReturnStrongest = 0x37;
inline constexpr std::uint8_t kReturnLast = 0x38;
inline constexpr std::uint8_t kReturnDual = 0x39;
inline constexpr std::uint8_t kProductVlp16 = 0x22;
inline constexpr std::uint8_t kProductEarlyFirmware = 0x21;  // early VLP-16 firmware reported the HDL-32E id

inline constexpr double kDistanceUnit = 0.002;  // metres per count
inline constexpr double kAzimuthUnitDeg = 0.01;
inline constexpr double kFiringPeriodUs = 2.304;     // between lasers of a sequence
inline constexpr double kSequencePeriodUs = 55.296;  // between firing sequences (includes recharge)
inline constexpr double kBlockPeriodUs = 2 * kSequencePeriodUs;
inline constexpr double kPacketPeriodUs = kBlocks * kBlockPeriodUs;  // 1327.104 µs → 753.5 packets/s

inline constexpr std::uint16_t kDataPort = 2368;
inline constexpr std::uint16_t kPositionPort = 8308;
inline constexpr std::size_t kPositionPacketSize = 512;
inline constexpr std::size_t kPositionTimestampOffset = 198;  // u32 µs past the hour
inline constexpr std::size_t kPositionPpsOffset = 202;        // u8: 0 absent, 1 synchronising, 2 locked, 3 error
inline constexpr std::size_t kPositionNmeaOffset = 206;       // NUL-padded $GPRMC sentence
inline constexpr std::size_t kPositionNmeaMax = 128;

// Laser id (channel in the block) → elevation and vertical offset, from the VLP-16 manual
// (and ../shared/data/vlp16/vlp16_lasers.csv). Channel order interleaves -15°, 1°, -13°, 3°, ...
struct LaserSpec {
  double elevation_deg;
  double vertical_offset_m;  // added to z of the point (ROS velodyne "vert_offset_correction")
};
inline constexpr std::array<LaserSpec, kLasers> kLaserTable{{{-15, 0.0112},
                                                             {1, -0.0007},
                                                             {-13, 0.0097},
                                                             {3, -0.0022},
                                                             {-11, 0.0081},
                                                             {5, -0.0037},
                                                             {-9, 0.0066},
                                                             {7, -0.0051},
                                                             {-7, 0.0051},
                                                             {9, -0.0066},
                                                             {-5, 0.0037},
                                                             {11, -0.0081},
                                                             {-3, 0.0022},
                                                             {13, -0.0097},
                                                             {-1, 0.0007},
                                                             {15, -0.0112}}};

// Ring index (0 = lowest beam) of a laser id, as ROS velodyne numbers rings.
inline constexpr std::uint16_t ring_of_laser(std::size_t laser) {
  return static_cast<std::uint16_t>(laser % 2 == 0 ? laser / 2 : 8 + laser / 2);
}

inline std::uint16_t read_u16(std::span<const std::uint8_t> b, std::size_t at) {
  return static_cast<std::uint16_t>(b[at] | (b[at + 1] << 8));
}
inline std::uint32_t read_u32(std::span<const std::uint8_t> b, std::size_t at) {
  return static_cast<std::uint32_t>(b[at]) | (static_cast<std::uint32_t>(b[at + 1]) << 8) |
         (static_cast<std::uint32_t>(b[at + 2]) << 16) | (static_cast<std::uint32_t>(b[at + 3]) << 24);
}
inline void write_u16(std::span<std::uint8_t> b, std::size_t at, std::uint16_t v) {
  b[at] = static_cast<std::uint8_t>(v & 0xFF);
  b[at + 1] = static_cast<std::uint8_t>(v >> 8);
}
inline void write_u32(std::span<std::uint8_t> b, std::size_t at, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) b[at + static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(v >> (8 * i));
}

// Byte offset of the distance of `laser` in firing sequence `seq` (0/1) of block `block`.
inline constexpr std::size_t channel_offset(std::size_t block, std::size_t seq, std::size_t laser) {
  return block * kBlockSize + 4 + (seq * kLasers + laser) * 3;
}

}  // namespace fsd::wire::vlp16
