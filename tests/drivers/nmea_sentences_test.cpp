// Sentence parsers on real-world sentences, every field asserted against the text by hand.
// Sources: gpsinformation.org examples, Trimble's GGA reference example, an NTRIP caster's test set of rover
// GGAs (RTK fixed near Paris), a ship's bridge log (RMC/GGA/VTG/HDT/ROT), a GNSS-INS stream with PASHR and ROT
// (GN talker, 2022), gpsd's Hemisphere (no fix) and Septentrio PolarRx2 logs, Applanix/Trimble PASHR examples.
#include <gtest/gtest.h>

#include <string>

#include "common/wire/nmea.hpp"
#include "drivers/gnss/nmea_sentences.hpp"

namespace fsd {
namespace {

ParsedSentence parse_line(const std::string& line) {
  const nmea::Unframed u = nmea::unframe(line);
  EXPECT_EQ(u.error, nmea::FrameError::None) << line;
  return parse_sentence(u.payload);
}

template <class T>
T parse_as(const std::string& line) {
  const ParsedSentence p = parse_line(line);
  EXPECT_EQ(p.error, SentenceError::None) << line;
  const T* s = std::get_if<T>(&p.sentence);
  EXPECT_NE(s, nullptr) << line;
  return s ? *s : T{};
}

double hms(int h, int m, double s) { return h * 3600.0 + m * 60.0 + s; }

TEST(NmeaGga, ClassicSinglePointExample) {
  const auto g = parse_as<GgaSentence>("$GPGGA,123519,4807.038,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,,*47");
  EXPECT_DOUBLE_EQ(*g.utc_s, hms(12, 35, 19));
  EXPECT_DOUBLE_EQ(*g.lat_deg, 48.1173);
  EXPECT_DOUBLE_EQ(*g.lon_deg, 11.0 + 31.0 / 60.0);
  EXPECT_EQ(g.quality, 1);
  EXPECT_EQ(g.satellites, 8);
  EXPECT_DOUBLE_EQ(*g.hdop, 0.9);
  EXPECT_DOUBLE_EQ(*g.altitude_msl_m, 545.4);
  EXPECT_DOUBLE_EQ(*g.geoid_separation_m, 46.9);
  EXPECT_FALSE(g.diff_age_s);
  EXPECT_FALSE(g.station_id);
}

TEST(NmeaGga, TrimbleDifferentialExample) {
  const ParsedSentence p =
      parse_line("$GPGGA,172814.0,3723.46587704,N,12202.26957864,W,2,6,1.2,18.893,M,-25.669,M,2.0,0031*4F");
  EXPECT_EQ(std::string(p.talker), "GP");
  const auto& g = std::get<GgaSentence>(p.sentence);
  EXPECT_DOUBLE_EQ(*g.utc_s, hms(17, 28, 14));
  EXPECT_DOUBLE_EQ(*g.lat_deg, 37.0 + 23.46587704 / 60.0);
  EXPECT_DOUBLE_EQ(*g.lon_deg, -(122.0 + 2.26957864 / 60.0));
  EXPECT_EQ(g.quality, 2);
  EXPECT_EQ(g.satellites, 6);
  EXPECT_DOUBLE_EQ(*g.hdop, 1.2);
  EXPECT_DOUBLE_EQ(*g.altitude_msl_m, 18.893);
  EXPECT_DOUBLE_EQ(*g.geoid_separation_m, -25.669);
  EXPECT_DOUBLE_EQ(*g.diff_age_s, 2.0);
  EXPECT_EQ(g.station_id, 31);
}

TEST(NmeaGga, RtkFixedAndFloatFromRovers) {
  const auto fixed =
      parse_as<GgaSentence>("$GNGGA,205655.60,4849.4770477,N,00220.6693234,E,4,12,0.63,60.806,M,46.188,M,14.6,0000*6E");
  EXPECT_DOUBLE_EQ(*fixed.utc_s, hms(20, 56, 55.6));
  EXPECT_DOUBLE_EQ(*fixed.lat_deg, 48.0 + 49.4770477 / 60.0);
  EXPECT_DOUBLE_EQ(*fixed.lon_deg, 2.0 + 20.6693234 / 60.0);
  EXPECT_EQ(fixed.quality, 4);
  EXPECT_EQ(fixed.satellites, 12);
  EXPECT_DOUBLE_EQ(*fixed.hdop, 0.63);
  EXPECT_DOUBLE_EQ(*fixed.altitude_msl_m, 60.806);
  EXPECT_DOUBLE_EQ(*fixed.geoid_separation_m, 46.188);
  EXPECT_DOUBLE_EQ(*fixed.diff_age_s, 14.6);
  EXPECT_EQ(fixed.station_id, 0);

  const auto flt =
      parse_as<GgaSentence>("$GNGGA,114835.60,5742.5522736,N,01156.8392494,E,5,15,1.1,5.18,M,35.78,M,,*77");
  EXPECT_EQ(flt.quality, 5);
  EXPECT_EQ(flt.satellites, 15);
  EXPECT_DOUBLE_EQ(*flt.lat_deg, 57.0 + 42.5522736 / 60.0);
  EXPECT_FALSE(flt.diff_age_s);
}

TEST(NmeaGga, NoFixHasEmptyFields) {
  const auto g = parse_as<GgaSentence>("$GPGGA,,,,,,0,,,,M,,M,,*66");  // Hemisphere receiver before its first fix
  EXPECT_FALSE(g.utc_s);
  EXPECT_FALSE(g.lat_deg);
  EXPECT_FALSE(g.lon_deg);
  EXPECT_EQ(g.quality, 0);
  EXPECT_FALSE(g.satellites);
  EXPECT_FALSE(g.hdop);
  EXPECT_FALSE(g.altitude_msl_m);
}

TEST(NmeaGga, TwoDimensionalFixWithoutAltitude) {
  // Septentrio PolarRx2 with 3 satellites: position but no altitude or geoid fields.
  const auto g = parse_as<GgaSentence>("$GPGGA,112257.00,3844.24011,N,00908.43828,W,1,03,10.5,,,,,,*72");
  EXPECT_DOUBLE_EQ(*g.lon_deg, -(9.0 + 8.43828 / 60.0));
  EXPECT_EQ(g.satellites, 3);
  EXPECT_DOUBLE_EQ(*g.hdop, 10.5);
  EXPECT_FALSE(g.altitude_msl_m);
  EXPECT_FALSE(g.geoid_separation_m);
}

TEST(NmeaRmc, ShipsLogAndClassicExample) {
  const auto r = parse_as<RmcSentence>("$GPRMC,000001,A,4610.2061,S,05205.1274,E,06.4,224.191,311216,,,D*54");
  EXPECT_DOUBLE_EQ(*r.utc_s, 1.0);
  EXPECT_TRUE(r.valid);
  EXPECT_DOUBLE_EQ(*r.lat_deg, -(46.0 + 10.2061 / 60.0));
  EXPECT_DOUBLE_EQ(*r.lon_deg, 52.0 + 5.1274 / 60.0);
  EXPECT_DOUBLE_EQ(*r.speed_knots, 6.4);
  EXPECT_DOUBLE_EQ(*r.course_deg, 224.191);
  EXPECT_EQ(r.date, (nmea::Date{2016, 12, 31}));
  EXPECT_EQ(r.mode, 'D');

  const auto c = parse_as<RmcSentence>("$GPRMC,123519,A,4807.038,N,01131.000,E,022.4,084.4,230394,003.1,W*6A");
  EXPECT_DOUBLE_EQ(*c.speed_knots, 22.4);
  EXPECT_DOUBLE_EQ(*c.course_deg, 84.4);
  EXPECT_EQ(c.date, (nmea::Date{1994, 3, 23}));
  EXPECT_EQ(c.mode, 0);
}

TEST(NmeaRmc, Nmea41WithEmptySpeedAndNavStatus) {
  const auto r = parse_as<RmcSentence>("$GNRMC,114835.60,A,5742.5522736,N,01156.8392494,E,,,191022,,W,D,V*61");
  EXPECT_DOUBLE_EQ(*r.utc_s, hms(11, 48, 35.6));
  EXPECT_TRUE(r.valid);
  EXPECT_FALSE(r.speed_knots);
  EXPECT_FALSE(r.course_deg);
  EXPECT_EQ(r.date, (nmea::Date{2022, 10, 19}));
  EXPECT_EQ(r.mode, 'D');
}

TEST(NmeaVtg, WithAndWithoutData) {
  const auto v = parse_as<VtgSentence>("$GPVTG,224.2,T,,M,06.43,N,11.91,K,D*07");
  EXPECT_DOUBLE_EQ(*v.course_deg, 224.2);
  EXPECT_DOUBLE_EQ(*v.speed_knots, 6.43);
  EXPECT_DOUBLE_EQ(*v.speed_kmh, 11.91);
  EXPECT_EQ(v.mode, 'D');
  const auto n = parse_as<VtgSentence>("$GPVTG,,T,,M,,N,,K,N*2C");
  EXPECT_FALSE(n.course_deg);
  EXPECT_FALSE(n.speed_knots);
  EXPECT_FALSE(n.speed_kmh);
  EXPECT_EQ(n.mode, 'N');
  const auto s = parse_as<VtgSentence>("$GPVTG,339.1,T,333.5,M,0.1,N,0.1,K,A*2D");
  EXPECT_DOUBLE_EQ(*s.course_deg, 339.1);
}

TEST(NmeaHdtRot, ShipsGyroAndInsStream) {
  EXPECT_DOUBLE_EQ(*parse_as<HdtSentence>("$GPHDT,232.39,T*0C").heading_deg, 232.39);
  EXPECT_FALSE(parse_as<HdtSentence>("$GPHDT,,T*1B").heading_deg);
  const auto rot = parse_as<RotSentence>("$GPROT,-000.16,A*2B");
  EXPECT_DOUBLE_EQ(*rot.rate_deg_per_min, -0.16);
  EXPECT_TRUE(rot.valid);
  const auto bad = parse_as<RotSentence>("$GNROT,0.0,V*38");
  EXPECT_DOUBLE_EQ(*bad.rate_deg_per_min, 0.0);
  EXPECT_FALSE(bad.valid);
}

TEST(NmeaPashr, ApplanixTrimbleExample) {
  const ParsedSentence p = parse_line("$PASHR,085335.000,224.19,T,-01.26,+00.83,+00.00,0.101,0.113,0.267,1,0*06");
  EXPECT_EQ(std::string(p.talker), "");
  const auto& a = std::get<PashrSentence>(p.sentence);
  EXPECT_DOUBLE_EQ(*a.utc_s, hms(8, 53, 35));
  EXPECT_DOUBLE_EQ(*a.heading_deg, 224.19);
  EXPECT_DOUBLE_EQ(*a.roll_deg, -1.26);
  EXPECT_DOUBLE_EQ(*a.pitch_deg, 0.83);
  EXPECT_DOUBLE_EQ(*a.heave_m, 0.0);
  EXPECT_DOUBLE_EQ(*a.roll_sigma_deg, 0.101);
  EXPECT_DOUBLE_EQ(*a.pitch_sigma_deg, 0.113);
  EXPECT_DOUBLE_EQ(*a.heading_sigma_deg, 0.267);
  EXPECT_EQ(a.gnss_quality, 1);
  EXPECT_EQ(a.imu_status, 0);
}

TEST(NmeaPashr, EmptyPitchFromInsStream) {
  const auto a = parse_as<PashrSentence>("$PASHR,070559.61,319.50,T,-37.37,,,0.853,,2.234,1,*2C");
  EXPECT_DOUBLE_EQ(*a.utc_s, hms(7, 5, 59.61));
  EXPECT_DOUBLE_EQ(*a.heading_deg, 319.5);
  EXPECT_DOUBLE_EQ(*a.roll_deg, -37.37);
  EXPECT_FALSE(a.pitch_deg);
  EXPECT_FALSE(a.heave_m);
  EXPECT_DOUBLE_EQ(*a.heading_sigma_deg, 2.234);
  EXPECT_FALSE(a.imu_status);
}

TEST(NmeaSentence, UnsupportedAndBadAddresses) {
  EXPECT_EQ(parse_line("$GPGSV,5,1,17,02,46,305,,04,74,240,,05,14,290,,07,46,134,*74").error,
            SentenceError::Unsupported);
  EXPECT_EQ(parse_line("$GNZDA,114835.60,19,10,2022,,*7F").error, SentenceError::Unsupported);
  EXPECT_EQ(parse_line("$GNTHS,319.50,V*00").error, SentenceError::Unsupported);
  EXPECT_EQ(parse_sentence("PASHR,POS,0,10,123519.00,4807.038,N").error, SentenceError::Unsupported);
  EXPECT_EQ(parse_sentence("PGRME,15.0,M,45.0,M,25.0,M").error, SentenceError::Unsupported);
  EXPECT_EQ(parse_sentence("gpgga,123519,,,,,0").error, SentenceError::BadAddress);
  EXPECT_EQ(parse_sentence("GPGG,123519").error, SentenceError::BadAddress);
  EXPECT_EQ(parse_sentence("GPGGAX,123519").error, SentenceError::BadAddress);
  EXPECT_EQ(parse_sentence("").error, SentenceError::BadAddress);
  EXPECT_EQ(parse_sentence("P").error, SentenceError::BadAddress);
}

TEST(NmeaSentence, OtherTalkersAccepted) {
  for (const char* talker : {"GP", "GN", "GL", "GA", "GB", "BD", "HE", "IN"}) {
    const ParsedSentence p = parse_sentence(std::string(talker) + "HDT,10.5,T");
    EXPECT_EQ(p.error, SentenceError::None) << talker;
    EXPECT_EQ(std::string(p.talker), talker);
    EXPECT_EQ(type_of(p.sentence), SentenceType::HDT);
  }
}

TEST(NmeaSentence, MalformedFieldsRejected) {
  for (const char* payload : {
           "GPGGA,123519,4807.038,N,01131.000,E,X,08,0.9,545.4,M,46.9,M,,",   // quality not a number
           "GPGGA,123519,4807.038,N,01131.000,E,,08,0.9,545.4,M,46.9,M,,",    // quality missing
           "GPGGA,123519,4807.038,,01131.000,E,1,08,0.9,545.4,M,46.9,M,,",    // hemisphere missing
           "GPGGA,123519,4807.038,N,01131.000,E,1,08,-0.9,545.4,M,46.9,M,,",  // negative HDOP
           "GPGGA,12h519,4807.038,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,,",   // bad time
           "GPGGA,123519,4807.038,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,2.0 0031",
           "GPRMC,123519,X,4807.038,N,01131.000,E,022.4,084.4,230394,003.1,W",  // status
           "GPRMC,123519,A,4807.038,N,01131.000,E,022.4,084.4,320394,003.1,W",  // date
           "GPRMC,123519,,4807.038,N,01131.000,E,022.4,084.4,230394,003.1,W",
           "GPVTG,054.7,034.4,005.5,010.2",   // pre-2.0 layout
           "GPVTG,400.0,T,,M,1.0,N,1.9,K,A",  // course > 360
           "GPHDT,-5.0,T", "GPHDT,12.5,M", "GPROT,fast,A",
           "PASHR,085335.000,224.19,T,-01.26,+00.83,+00.00,0.101,0.113,0.267,x,0",
           "PASHR,085335.000,224.19,T,-01.26,+95.83,+00.00,0.101,0.113,0.267,1,0",  // pitch beyond 90
       })
    EXPECT_EQ(parse_sentence(payload).error, SentenceError::Malformed) << payload;
}

TEST(NmeaSentence, UtcOfTimedSentencesOnly) {
  EXPECT_DOUBLE_EQ(*utc_of(parse_sentence("GPGGA,123519,,,,,0,,,,M,,M,,").sentence), hms(12, 35, 19));
  EXPECT_DOUBLE_EQ(*utc_of(parse_sentence("PASHR,123519.020,1.0,T,0,0,0,0,0,0,4,1").sentence), hms(12, 35, 19.02));
  EXPECT_FALSE(utc_of(parse_sentence("GPHDT,12.5,T").sentence));
  EXPECT_FALSE(utc_of(parse_sentence("GPGGA,,,,,,0,,,,M,,M,,").sentence));
}

}  // namespace
}  // namespace fsd
