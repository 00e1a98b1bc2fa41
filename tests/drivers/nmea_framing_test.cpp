// NMEA 0183 framing and field codecs (common/wire/nmea) on real-world sentences. Sources of the sentences:
// the widely published GGA/RMC examples (gpsinformation.org), Trimble's GGA reference example, gpsd's
// regression logs (Hemisphere, Septentrio PolarRx2), a ship's bridge GPS log and an NTRIP caster's test set.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "common/wire/nmea.hpp"

namespace fsd::nmea {
namespace {

TEST(NmeaChecksum, MatchesPublishedExamples) {
  // The classic GGA example whose checksum is printed as *47.
  EXPECT_EQ(checksum("GPGGA,123519,4807.038,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,,"), 0x47);
  EXPECT_EQ(checksum("GPHDT,232.39,T"), 0x0C);
  EXPECT_EQ(checksum(""), 0x00);
}

TEST(NmeaUnframe, AcceptsRealSentences) {
  const std::vector<std::string> lines = {
      "$GPGGA,123519,4807.038,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,,*47",
      "$GPRMC,123519,A,4807.038,N,01131.000,E,022.4,084.4,230394,003.1,W*6A",
      "$GPGGA,172814.0,3723.46587704,N,12202.26957864,W,2,6,1.2,18.893,M,-25.669,M,2.0,0031*4F",
      "$GNGGA,205655.60,4849.4770477,N,00220.6693234,E,4,12,0.63,60.806,M,46.188,M,14.6,0000*6E",
      "$PASHR,085335.000,224.19,T,-01.26,+00.83,+00.00,0.101,0.113,0.267,1,0*06",
      "$GPGGA,,,,,,0,,,,M,,M,,*66",
      "$GPROT,-000.16,A*2B",
  };
  for (const auto& l : lines) {
    const Unframed u = unframe(l);
    EXPECT_EQ(u.error, FrameError::None) << l;
    EXPECT_EQ(u.payload, std::string_view(l).substr(1, l.size() - 4)) << l;
  }
}

TEST(NmeaUnframe, RejectsBadChecksumsFoundInTheWild) {
  // This RTK example circulates in many tutorials with *40; the XOR of its payload is 0x5F.
  EXPECT_EQ(unframe("$GPGGA,181908.00,3404.7041778,N,07044.3966270,W,4,13,1.00,495.144,M,29.200,M,0.10,0000*40").error,
            FrameError::ChecksumMismatch);
  // Trimble's example with the comma before the station id turned into a space keeps the old checksum.
  EXPECT_EQ(unframe("$GPGGA,172814.0,3723.46587704,N,12202.26957864,W,2,6,1.2,18.893,M,-25.669,M,2.0 0031*4F").error,
            FrameError::ChecksumMismatch);
  EXPECT_EQ(unframe("$GPROT,35.6,A*FF").error, FrameError::ChecksumMismatch);
  EXPECT_EQ(unframe("$GPROT,35.6,A*").error, FrameError::MalformedChecksum);
  EXPECT_EQ(unframe("$GPROT,35.6,A*0").error, FrameError::MalformedChecksum);
  EXPECT_EQ(unframe("$GPROT,35.6,A*011").error, FrameError::MalformedChecksum);
  EXPECT_EQ(unframe("$GPROT,35.6,A*G1").error, FrameError::MalformedChecksum);
  EXPECT_EQ(unframe("GPGGA,123519*47").error, FrameError::NoStart);
  EXPECT_EQ(unframe("").error, FrameError::NoStart);
  EXPECT_EQ(unframe("$GPROT,35.6,A").error, FrameError::MissingChecksum);
}

TEST(NmeaUnframe, OptionalChecksumAndLowerCaseHex) {
  const Unframed u = unframe("$GPROT,35.6,A", false);
  EXPECT_EQ(u.error, FrameError::None);
  EXPECT_EQ(u.payload, "GPROT,35.6,A");
  EXPECT_EQ(unframe("$GPHDT,232.39,T*0c").error, FrameError::None);
}

TEST(NmeaBuild, ReproducesRealSentencesByteForByte) {
  EXPECT_EQ(frame("GPHDT,232.39,T"), "$GPHDT,232.39,T*0C\r\n");
  const std::vector<std::string> rot = {"-000.16", "A"};
  EXPECT_EQ(build("GPROT", rot), "$GPROT,-000.16,A*2B\r\n");
  const std::vector<std::string> gga = {"123519", "4807.038", "N", "01131.000", "E", "1", "08",
                                        "0.9",    "545.4",    "M", "46.9",      "M", "",  ""};
  EXPECT_EQ(build("GPGGA", gga), "$GPGGA,123519,4807.038,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,,*47\r\n");
}

TEST(NmeaFields, SplitsEmptyAndMissingTrailingFields) {
  const Fields f("GPGGA,,,,,,0,,,,M,,M,,");
  ASSERT_EQ(f.size(), 15u);
  EXPECT_FALSE(f.overflow());
  EXPECT_EQ(f[0], "GPGGA");
  EXPECT_EQ(f[1], "");
  EXPECT_EQ(f[6], "0");
  EXPECT_EQ(f[10], "M");
  EXPECT_EQ(f[14], "");
  EXPECT_EQ(f[15], "");  // past the end reads empty
  EXPECT_EQ(f[1000], "");
  EXPECT_EQ(Fields("").size(), 1u);
  EXPECT_TRUE(Fields(std::string(60, ',')).overflow());
}

TEST(NmeaCodecs, Decimal) {
  EXPECT_EQ(parse_decimal("+00.83"), 0.83);
  EXPECT_EQ(parse_decimal("-01.26"), -1.26);
  EXPECT_EQ(parse_decimal("-000.16"), -0.16);
  EXPECT_EQ(parse_decimal("545.4"), 545.4);
  EXPECT_EQ(parse_decimal(".5"), 0.5);
  EXPECT_EQ(parse_decimal("5."), 5.0);
  for (const char* bad : {"", "+", "-", ".", "1.2.3", "1e5", "inf", "nan", "0x10", " 1", "1 ", "--1", "1,0"})
    EXPECT_FALSE(parse_decimal(bad)) << bad;
}

TEST(NmeaCodecs, Integer) {
  EXPECT_EQ(parse_integer("08"), 8);
  EXPECT_EQ(parse_integer("0031"), 31);
  for (const char* bad : {"", "-1", "+1", "1.0", "AAAA", "1234567890"}) EXPECT_FALSE(parse_integer(bad)) << bad;
}

TEST(NmeaCodecs, LatitudeLongitudeByHand) {
  EXPECT_DOUBLE_EQ(*parse_latitude("4807.038", "N"), 48.0 + 7.038 / 60.0);
  EXPECT_DOUBLE_EQ(*parse_longitude("01131.000", "E"), 11.0 + 31.0 / 60.0);
  EXPECT_DOUBLE_EQ(*parse_latitude("3723.46587704", "N"), 37.0 + 23.46587704 / 60.0);
  EXPECT_DOUBLE_EQ(*parse_longitude("12202.26957864", "W"), -(122.0 + 2.26957864 / 60.0));
  EXPECT_DOUBLE_EQ(*parse_latitude("4610.2061", "S"), -(46.0 + 10.2061 / 60.0));
  EXPECT_DOUBLE_EQ(*parse_longitude("00908.43828", "W"), -(9.0 + 8.43828 / 60.0));
  EXPECT_DOUBLE_EQ(*parse_latitude("0000.0000000", "N"), 0.0);
  EXPECT_DOUBLE_EQ(*parse_latitude("9000.0000", "S"), -90.0);
  // Hemisphere missing or wrong, minutes ≥ 60, beyond the pole, garbage.
  for (auto [v, h] : std::vector<std::pair<const char*, const char*>>{{"4807.038", ""},
                                                                      {"4807.038", "E"},
                                                                      {"4860.000", "N"},
                                                                      {"9100.000", "N"},
                                                                      {"48x7.038", "N"},
                                                                      {"-4807.038", "N"},
                                                                      {"7.038", "N"},
                                                                      {"", "N"},
                                                                      {"4807.038", "NN"}})
    EXPECT_FALSE(parse_latitude(v, h)) << v << " " << h;
  EXPECT_FALSE(parse_longitude("18100.000", "E"));
  EXPECT_FALSE(parse_longitude("01131.000", "N"));
}

TEST(NmeaCodecs, TimeOfDay) {
  EXPECT_DOUBLE_EQ(*parse_time_of_day("123519"), 12 * 3600 + 35 * 60 + 19);
  EXPECT_DOUBLE_EQ(*parse_time_of_day("172814.0"), 17 * 3600 + 28 * 60 + 14);
  EXPECT_DOUBLE_EQ(*parse_time_of_day("205655.60"), 20 * 3600 + 56 * 60 + 55.6);
  EXPECT_DOUBLE_EQ(*parse_time_of_day("085335.000"), 8 * 3600 + 53 * 60 + 35);
  EXPECT_DOUBLE_EQ(*parse_time_of_day("235960"), 23 * 3600 + 59 * 60 + 60);  // leap second
  EXPECT_DOUBLE_EQ(*parse_time_of_day("000001."), 1.0);
  for (const char* bad : {"", "12351", "246000", "126000", "123561", "12:35:19", "123519,5", "123519.5a", "a23519"})
    EXPECT_FALSE(parse_time_of_day(bad)) << bad;
}

TEST(NmeaCodecs, Date) {
  EXPECT_EQ(parse_date("230394"), (Date{1994, 3, 23}));
  EXPECT_EQ(parse_date("311216"), (Date{2016, 12, 31}));
  EXPECT_EQ(parse_date("191022"), (Date{2022, 10, 19}));
  EXPECT_EQ(parse_date("290224"), (Date{2024, 2, 29}));
  for (const char* bad : {"", "310216", "290223", "001224", "011324", "1912022", "19102"})
    EXPECT_FALSE(parse_date(bad)) << bad;
  EXPECT_EQ(format_date({2016, 12, 31}), "311216");
  EXPECT_EQ(format_date({2024, 8, 7}), "070824");
}

TEST(NmeaCodecs, FormatCoordinates) {
  auto c = format_latitude(48.1173, 4);
  EXPECT_EQ(c.value, "4807.0380");
  EXPECT_EQ(c.hemisphere, "N");
  c = format_longitude(-(11.0 + 31.0 / 60.0), 3);
  EXPECT_EQ(c.value, "01131.000");
  EXPECT_EQ(c.hemisphere, "W");
  c = format_latitude(-(46.0 + 10.2061 / 60.0), 4);
  EXPECT_EQ(c.value, "4610.2061");
  EXPECT_EQ(c.hemisphere, "S");
  // 0.99999999999° is 59.9999999994', which rounds up to the next whole degree.
  c = format_latitude(0.99999999999, 8);
  EXPECT_EQ(c.value, "0100.00000000");
  c = format_longitude(8.5658, 8);
  EXPECT_EQ(c.value, "00833.94800000");
  EXPECT_EQ(c.hemisphere, "E");
  EXPECT_EQ(format_latitude(0.0, 2).value, "0000.00");
}

TEST(NmeaCodecs, FormatTimeAndNumbers) {
  EXPECT_EQ(format_time_of_day(12 * 3600 + 35 * 60 + 19.5, 2), "123519.50");
  EXPECT_EQ(format_time_of_day(1.0, 3), "000001.000");
  EXPECT_EQ(format_time_of_day(86399.999, 2), "000000.00");  // rounds over midnight
  EXPECT_EQ(format_time_of_day(86400 + 61.25, 2), "000101.25");
  EXPECT_EQ(format_time_of_day(-1.0, 0), "235959");
  EXPECT_EQ(format_fixed(-1.256, 2), "-1.26");
  EXPECT_EQ(format_fixed(0.83, 2, true), "+0.83");
  EXPECT_EQ(format_fixed(224.19, 3), "224.190");
}

}  // namespace
}  // namespace fsd::nmea
