#pragma once
// VLP-16 position packets (512 bytes, UDP port 8308): the sensor's clock, its PPS lock state and the $GPRMC
// sentence it received from a GPS. Only the sentence text is extracted and its checksum verified here; NMEA
// parsing belongs to the GNSS driver.
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

namespace fsd {

enum class PpsState : std::uint8_t { Absent = 0, Synchronizing = 1, Locked = 2, Error = 3 };
std::string_view to_string(PpsState s);

enum class NmeaState : std::uint8_t {
  Absent,       // no sentence (no GPS connected): the field is all NUL
  Valid,        // "$...*hh" with a matching checksum
  BadChecksum,  // well formed but the XOR checksum differs
  Malformed     // no '$' start, no "*hh", unprintable bytes or no NUL terminator within the field
};
std::string_view to_string(NmeaState s);

struct PositionPacket {
  std::uint32_t timestamp_us = 0;  // µs past the hour
  PpsState pps = PpsState::Absent;
  std::string nmea;  // the sentence without trailing CR/LF ("" when absent)
  NmeaState nmea_state = NmeaState::Absent;
};

enum class PositionStatus : std::uint8_t { Ok, WrongSize, BadPpsState };
std::string_view to_string(PositionStatus s);

struct PositionCounters {
  std::uint64_t packets = 0, wrong_size = 0, bad_pps_state = 0;
  std::uint64_t nmea_valid = 0, nmea_absent = 0, nmea_bad_checksum = 0, nmea_malformed = 0;
  std::uint64_t rejected() const { return wrong_size + bad_pps_state; }
};

// Validates and parses one UDP payload; fills `out` only when Ok. A bad sentence does not reject the packet
// (timestamp and PPS stay useful): it shows in nmea_state.
PositionStatus parse_position_packet(std::span<const std::uint8_t> packet, PositionPacket& out);

// True for "$<body>*hh" where hh (hex, either case) is the XOR of the body's bytes.
bool nmea_checksum_ok(std::string_view sentence);

// parse_position_packet plus counters, for one owner thread.
class PositionPacketParser {
 public:
  PositionStatus parse(std::span<const std::uint8_t> packet, PositionPacket& out);
  const PositionCounters& counters() const { return counters_; }

 private:
  PositionCounters counters_;
};

}  // namespace fsd
