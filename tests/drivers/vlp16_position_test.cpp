// VLP-16 position packets: timestamp, PPS state, the $GPRMC sentence and its checksum.
#include <gtest/gtest.h>

#include <string>

#include "drivers/vlp16/position_packet.hpp"
#include "tests/drivers/vlp16_test_packets.hpp"

namespace fsd {
namespace {

using test::position_packet_bytes;

// The textbook RMC sentence (NMEA 0183 reference); XOR of the characters between '$' and '*' is 0x6A.
const std::string kRmc = "$GPRMC,123519,A,4807.038,N,01131.000,E,022.4,084.4,230394,003.1,W*6A";

TEST(Vlp16Position, ParsesTimestampPpsAndSentence) {
  const auto bytes = position_packet_bytes(1'234'567'890u, 2, kRmc + "\r\n");
  PositionPacket p;
  ASSERT_EQ(parse_position_packet(bytes, p), PositionStatus::Ok);
  EXPECT_EQ(p.timestamp_us, 1'234'567'890u);
  EXPECT_EQ(p.pps, PpsState::Locked);
  EXPECT_EQ(p.nmea, kRmc);  // without CR LF
  EXPECT_EQ(p.nmea_state, NmeaState::Valid);
}

TEST(Vlp16Position, ChecksumAndSentenceProblemsDoNotRejectThePacket) {
  PositionPacketParser parser;
  PositionPacket p;
  std::string wrong = kRmc;
  wrong[8] = '4';  // 123519 → 143519: checksum no longer matches
  ASSERT_EQ(parser.parse(position_packet_bytes(1, 1, wrong), p), PositionStatus::Ok);
  EXPECT_EQ(p.nmea_state, NmeaState::BadChecksum);
  EXPECT_EQ(p.pps, PpsState::Synchronizing);

  ASSERT_EQ(parser.parse(position_packet_bytes(2, 0, ""), p), PositionStatus::Ok);  // no GPS connected
  EXPECT_EQ(p.nmea_state, NmeaState::Absent);
  EXPECT_EQ(p.timestamp_us, 2u);

  ASSERT_EQ(parser.parse(position_packet_bytes(3, 0, "GPRMC,no dollar*00"), p), PositionStatus::Ok);
  EXPECT_EQ(p.nmea_state, NmeaState::Malformed);
  ASSERT_EQ(parser.parse(position_packet_bytes(4, 0, "$GPRMC,\x01\x02*00"), p), PositionStatus::Ok);
  EXPECT_EQ(p.nmea_state, NmeaState::Malformed);
  ASSERT_EQ(parser.parse(position_packet_bytes(5, 0, std::string(128, 'A')), p), PositionStatus::Ok);  // no NUL
  EXPECT_EQ(p.nmea_state, NmeaState::Malformed);

  const auto& c = parser.counters();
  EXPECT_EQ(c.packets, 5u);
  EXPECT_EQ(c.nmea_bad_checksum, 1u);
  EXPECT_EQ(c.nmea_absent, 1u);
  EXPECT_EQ(c.nmea_malformed, 3u);
  EXPECT_EQ(c.rejected(), 0u);
}

TEST(Vlp16Position, RejectsWrongSizeAndPpsState) {
  PositionPacketParser parser;
  PositionPacket p;
  auto bytes = position_packet_bytes(1, 0, kRmc);
  bytes.pop_back();
  EXPECT_EQ(parser.parse(bytes, p), PositionStatus::WrongSize);
  EXPECT_EQ(parser.parse(std::vector<std::uint8_t>(1206, 0), p), PositionStatus::WrongSize);
  EXPECT_EQ(parser.parse(position_packet_bytes(1, 4, kRmc), p), PositionStatus::BadPpsState);
  EXPECT_EQ(parser.counters().wrong_size, 2u);
  EXPECT_EQ(parser.counters().bad_pps_state, 1u);
  EXPECT_EQ(parser.counters().packets, 0u);
}

TEST(Vlp16Position, NmeaChecksum) {
  EXPECT_TRUE(nmea_checksum_ok(kRmc));
  EXPECT_TRUE(nmea_checksum_ok("$GPRMC,123519,A,4807.038,N,01131.000,E,022.4,084.4,230394,003.1,W*6a"));
  EXPECT_FALSE(nmea_checksum_ok("$GPRMC,123519,A,4807.038,N,01131.000,E,022.4,084.4,230394,003.1,W*6B"));
  EXPECT_FALSE(nmea_checksum_ok("$GPRMC*"));
  EXPECT_FALSE(nmea_checksum_ok(""));
  EXPECT_TRUE(nmea_checksum_ok("$*00"));  // empty body: XOR of nothing is 0
}

}  // namespace
}  // namespace fsd
