// GNSS-INS driver: bytes in, samples out. Real receiver output (a GNSS-INS stream with PASHR and ROT, rover GGAs
// sent to an NTRIP caster, a Hemisphere log without fix), broken framing, and the conversions checked by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "common/wire/nmea.hpp"
#include "drivers/gnss/gnss_driver.hpp"

namespace fsd {
namespace {

struct Harness {
  explicit Harness(const GnssConfig& c) : driver(c, [this](const GnssSample& s) { samples.push_back(s); }) {}
  void feed(const std::string& text, Stamp t) {
    driver.feed({reinterpret_cast<const std::uint8_t*>(text.data()), text.size()}, t);
  }
  std::vector<GnssSample> samples;
  GnssDriver driver;
};

std::string line(const std::string& payload) { return nmea::frame(payload); }

GnssConfig no_lever() {
  GnssConfig c;
  c.antenna_x = c.antenna_y = c.antenna_z = 0.0;
  return c;
}

// Textbook radii of curvature of WGS-84 for small offsets: north = M Δφ, east = N cos φ Δλ.
struct Radii {
  double m, n;
};
Radii radii(double lat_deg) {
  const double a = 6378137.0, f = 1 / 298.257223563, e2 = f * (2 - f);
  const double s = std::sin(deg2rad(lat_deg));
  const double w = std::sqrt(1 - e2 * s * s);
  return {a * (1 - e2) / (w * w * w), a / w};
}

// A GNSS-INS in an RTK float solution, two epochs (tag blocks of the recording removed, order as recorded).
const std::string kInsEpochA =
    "$GNGSA,M,1,04,06,07,09,11,16,20,,,,,,1.53,1.09,1.07,1*0F\r\n"
    "$GNGGA,114835.60,5742.5522736,N,01156.8392494,E,5,15,1.1,5.18,M,35.78,M,,*77\r\n"
    "$GNVTG,,T,,M,,N,,K,A*3D\r\n"
    "$PASHR,114835.60,027.23,T,-75.83,,,3.158,,4.831,1,*22\r\n"
    "$GNRMC,114835.60,A,5742.5522736,N,01156.8392494,E,,,191022,,W,D,V*61\r\n"
    "$GNZDA,114835.60,19,10,2022,,*7F\r\n"
    "$GNGST,114835.60,,,,,0.264,0.170,0.334*47\r\n"
    "$GNTHS,27.23,V*3A\r\n"
    "$GNROT,0.0,V*38\r\n";
const std::string kInsEpochB =
    "$GNGSA,M,1,01,03,21,32,,,,,,,,,1.89,1.31,1.37,1*09\r\n"
    "$GNGGA,070559.61,5742.5507032,N,01156.8375806,E,5,11,1.3,1.74,M,35.78,M,,*70\r\n"
    "$GNVTG,166.99,T,166.99,M,0.11,N,0.20,K,D*3A\r\n"
    "$PASHR,070559.61,319.50,T,-37.37,,,0.853,,2.234,1,*2C\r\n"
    "$GNRMC,070559.61,A,5742.5507032,N,01156.8375806,E,0.11,166.99,201022,,W,D,V*65\r\n"
    "$GNZDA,070559.61,20,10,2022,,*70\r\n"
    "$GNGST,070559.61,,,,,0.109,0.133,0.212*48\r\n"
    "$GNROT,0.0,V*38\r\n"
    "$GNTHS,319.50,V*00\r\n";

GnssConfig origin_at_epoch_a() {
  GnssConfig c = no_lever();
  c.use_first_fix = false;
  c.origin_lat_deg = 57.0 + 42.5522736 / 60.0;
  c.origin_lon_deg = 11.0 + 56.8392494 / 60.0;
  c.origin_height_m = 5.18 + 35.78;
  return c;
}

void expect_epochs_a_b(const std::vector<GnssSample>& s) {
  ASSERT_EQ(s.size(), 2u);
  const GnssSample& a = s[0];
  EXPECT_DOUBLE_EQ(a.stamp, 100.0);
  EXPECT_EQ(a.fix_quality, 5);
  EXPECT_EQ(a.satellites, 15);
  EXPECT_DOUBLE_EQ(a.hdop, 1.1);
  EXPECT_DOUBLE_EQ(a.lat_deg, 57.0 + 42.5522736 / 60.0);
  EXPECT_DOUBLE_EQ(a.alt_m, 5.18 + 35.78);
  EXPECT_TRUE(a.heading_valid);  // from PASHR: the epoch has no HDT
  EXPECT_NEAR(a.heading, deg2rad(90.0 - 27.23), 1e-12);
  EXPECT_NEAR(a.heading_sigma, deg2rad(4.831), 1e-12);  // PASHR's heading accuracy, 1σ in degrees
  EXPECT_FALSE(a.velocity_valid);                       // VTG and RMC without speed
  EXPECT_FALSE(a.attitude_valid);                       // PASHR without pitch
  EXPECT_FALSE(a.yaw_rate_valid);                       // ROT status V
  EXPECT_TRUE(a.good);
  EXPECT_NEAR(a.enu.norm(), 0.0, 1e-9);

  const GnssSample& b = s[1];
  EXPECT_DOUBLE_EQ(b.stamp, 200.0);
  EXPECT_EQ(b.satellites, 11);
  EXPECT_TRUE(b.velocity_valid);
  EXPECT_NEAR(b.speed, 0.20 / 3.6, 1e-12);  // VTG km/h preferred over knots
  EXPECT_NEAR(b.course, deg2rad(90.0 - 166.99), 1e-12);
  EXPECT_NEAR(b.heading, deg2rad(90.0 - 319.50 + 360.0), 1e-12);
  EXPECT_NEAR(b.heading_sigma, deg2rad(2.234), 1e-12);
  const double lat = 57.0 + 42.5522736 / 60.0;
  const Radii r = radii(lat);
  EXPECT_NEAR(b.enu.y(), r.m * deg2rad((42.5507032 - 42.5522736) / 60.0), 1e-3);
  EXPECT_NEAR(b.enu.x(), r.n * std::cos(deg2rad(lat)) * deg2rad((56.8375806 - 56.8392494) / 60.0), 1e-3);
  EXPECT_NEAR(b.enu.z(), 1.74 - 5.18, 1e-3);
  EXPECT_TRUE(b.good);
}

TEST(GnssDriver, RealInsStreamTwoEpochs) {
  Harness h(origin_at_epoch_a());
  h.feed(kInsEpochA, 100.0);
  EXPECT_TRUE(h.samples.empty());  // the first epoch ends when the next one begins
  h.feed(kInsEpochB, 200.0);
  expect_epochs_a_b(h.samples);
  EXPECT_EQ(h.driver.epoch_ender(), SentenceType::ROT);
  const GnssCounters c = h.driver.counters();
  EXPECT_EQ(c.lines, 18u);
  EXPECT_EQ(c.sentences, 10u);
  EXPECT_EQ(c.unsupported, 8u);  // GSA, ZDA, GST, THS
  EXPECT_EQ(c.bad_checksum + c.malformed + c.framing.garbage_bytes + c.late_sentences, 0u);
  EXPECT_EQ(c.samples, 2u);
  EXPECT_EQ(c.good_samples, 2u);
}

std::string replace_all(std::string s, const std::string& from, const std::string& to) {
  for (std::size_t p = s.find(from); p != std::string::npos; p = s.find(from, p + to.size()))
    s.replace(p, from.size(), to);
  return s;
}

TEST(GnssDriver, LineEndingsAndChunkingDoNotMatter) {
  for (const std::string eol : {"\n", "\r", "\r\n", "\n\n"}) {
    Harness h(origin_at_epoch_a());
    h.feed(replace_all(kInsEpochA, "\r\n", eol), 100.0);
    h.feed(replace_all(kInsEpochB, "\r\n", eol), 200.0);
    SCOPED_TRACE(eol == "\r" ? "CR" : eol == "\n" ? "LF" : "CRLF");
    expect_epochs_a_b(h.samples);
  }
  Harness h(origin_at_epoch_a());
  for (char c : kInsEpochA) h.feed(std::string(1, c), 100.0);
  for (std::size_t i = 0; i < kInsEpochB.size(); i += 7) h.feed(kInsEpochB.substr(i, 7), 200.0);
  expect_epochs_a_b(h.samples);
}

TEST(GnssDriver, SentenceStampIsWhenItsDollarArrived) {
  GnssConfig c = no_lever();
  c.emit_on = "GGA";
  c.latency_s = 0.05;
  Harness h(c);
  const std::string gga = "$GNGGA,114835.60,5742.5522736,N,01156.8392494,E,5,15,1.1,5.18,M,35.78,M,,*77\r\n";
  h.feed(gga.substr(0, 10), 10.0);
  h.feed(gga.substr(10), 10.01);
  ASSERT_EQ(h.samples.size(), 1u);
  EXPECT_DOUBLE_EQ(h.samples[0].stamp, 10.0 - 0.05);
}

TEST(GnssDriver, BrokenInputIsCountedAndSkipped) {
  GnssConfig c = no_lever();
  c.emit_on = "HDT";
  Harness h(c);
  std::string in;
  in += std::string("\x00\xFFhello", 7);  // 7 garbage bytes before any sentence
  in += "$GPGGA,114835.60,5742.55";       // cut short by the next '$'
  in += "$GPHDT,232.39,T*0C\r\n";
  in += "$GPGGA," + std::string(200, '1') + "\r\n";  // overlong
  in += "$GPHDT,23\x01.39,T*0C\r\n";                 // control character inside
  in += "$GPROT,35.6,A*FF\r\n";                      // checksum mismatch
  in += "$GPGGA,181908.00,3404.7041778,N,07044.3966270,W,4,13,1.00,495.144,M,29.200,M,0.10,0000*40\r\n";
  in += "$GPROT,35.6,A*\r\n";               // malformed checksum
  in += "$GPROT,35.6,A\r\n";                // no checksum
  in += "$GPGSV,5,5,17,50,45,190,*43\r\n";  // unsupported
  in += line("GPHDT,-5.0,T");               // malformed field
  in += line("gpgga,1");                    // bad address
  in += "\r\n\r\n";
  in += "$GPHDT,232.39,T*0C";  // unterminated at the end: waits
  h.feed(in, 1.0);
  const GnssCounters k = h.driver.counters();
  EXPECT_EQ(k.framing.bytes, in.size());
  EXPECT_EQ(k.framing.garbage_bytes, 7u);
  EXPECT_EQ(k.framing.truncated_lines, 1u);
  EXPECT_EQ(k.framing.overlong_lines, 1u);
  EXPECT_EQ(k.framing.bad_character_lines, 1u);
  EXPECT_EQ(k.bad_checksum, 3u);
  EXPECT_EQ(k.missing_checksum, 1u);
  EXPECT_EQ(k.unsupported, 1u);
  EXPECT_EQ(k.malformed, 1u);
  EXPECT_EQ(k.bad_address, 1u);
  EXPECT_EQ(k.sentences, 1u);           // the HDT after the truncated GGA
  EXPECT_EQ(k.lines, 8u);               // complete lines that reached the checksum check
  EXPECT_EQ(k.epochs_without_gga, 1u);  // that HDT alone ended an epoch
  EXPECT_TRUE(h.samples.empty());
  h.feed("\r\n", 1.1);
  EXPECT_EQ(h.driver.counters().sentences, 2u);
}

TEST(GnssDriver, NoFixStreamGivesSamplesThatAreNotGood) {
  // Hemisphere receiver before its first fix (gpsd regression log): empty HDT, GGA quality 0, VTG mode N, ZDA.
  const std::string cycle =
      "$GPHDT,,T*1B\r\n$GPGGA,,,,,,0,,,,M,,M,,*66\r\n$GPVTG,,T,,M,,N,,K,N*2C\r\n"
      "$GPZDA,193913.00,07,09,2018,00,00*63\r\n";
  Harness h(GnssConfig{});
  for (int i = 0; i < 3; ++i) h.feed(cycle, i);
  ASSERT_EQ(h.samples.size(), 2u);  // no time in any sentence: an epoch ends when HDT comes again
  for (const auto& s : h.samples) {
    EXPECT_EQ(s.fix_quality, 0);
    EXPECT_FALSE(s.good);
    EXPECT_FALSE(s.heading_valid);
    EXPECT_FALSE(s.velocity_valid);
    EXPECT_EQ(s.enu, Vec3::Zero());
  }
  EXPECT_FALSE(h.driver.origin());
  EXPECT_EQ(h.driver.counters().malformed, 0u);
}

// One epoch: optional extra sentences, then a rover GGA that ends it.
GnssSample one_epoch(const GnssConfig& base, const std::string& before, const std::string& gga) {
  GnssConfig c = base;
  c.emit_on = "GGA";
  Harness h(c);
  h.feed(before + gga + "\r\n", 0.0);
  EXPECT_EQ(h.samples.size(), 1u);
  return h.samples.empty() ? GnssSample{} : h.samples[0];
}

const std::string kRtkFixedOldCorrections =
    "$GNGGA,205655.60,4849.4770477,N,00220.6693234,E,4,12,0.63,60.806,M,46.188,M,14.6,0000*6E";
const std::string kRtkFloat = "$GNGGA,104710.00,4832.5844943,N,00229.8320136,E,5,12,0.84,80.418,M,46.332,M,1.0,0000*5A";
const std::string kDgps = "$GNGGA,103841.00,4511.0762921,N,00544.9783512,E,2,12,0.79,217.897,M,47.399,M,2.0,0000*63";
const std::string kSingle = "$GNGGA,103812.00,4511.0814681,N,00544.9383397,E,1,12,0.70,226.973,M,47.399,M,,*4E";
const std::string kHdt = "$GPHDT,232.39,T*0C\r\n";

TEST(GnssDriver, GoodFlagThresholds) {
  const GnssConfig def;
  EXPECT_FALSE(one_epoch(def, kHdt, kRtkFixedOldCorrections).good);  // corrections 14.6 s old > 3 s
  GnssConfig old_ok = def;
  old_ok.max_diff_age_s = 20.0;
  EXPECT_TRUE(one_epoch(old_ok, kHdt, kRtkFixedOldCorrections).good);
  EXPECT_DOUBLE_EQ(one_epoch(def, kHdt, kRtkFixedOldCorrections).age_s, 14.6);

  EXPECT_TRUE(one_epoch(def, kHdt, kRtkFloat).good);
  EXPECT_FALSE(one_epoch(def, "", kRtkFloat).good);  // no heading in the epoch
  GnssConfig no_heading = def;
  no_heading.require_heading = false;
  EXPECT_TRUE(one_epoch(no_heading, "", kRtkFloat).good);

  EXPECT_FALSE(one_epoch(def, kHdt, kDgps).good);
  GnssConfig dgps = def;
  dgps.min_fix = "dgps";
  EXPECT_TRUE(one_epoch(dgps, kHdt, kDgps).good);
  EXPECT_FALSE(one_epoch(dgps, kHdt, kSingle).good);
  GnssConfig single = def;
  single.min_fix = "single";
  EXPECT_TRUE(one_epoch(single, kHdt, kSingle).good);
  GnssConfig fixed_only = def;
  fixed_only.min_fix = "rtk_fixed";
  EXPECT_FALSE(one_epoch(fixed_only, kHdt, kRtkFloat).good);

  GnssConfig many_sats = def;
  many_sats.min_satellites = 13;
  EXPECT_FALSE(one_epoch(many_sats, kHdt, kRtkFloat).good);  // 12 in use
  GnssConfig low_hdop = def;
  low_hdop.max_hdop = 0.8;
  EXPECT_FALSE(one_epoch(low_hdop, kHdt, kRtkFloat).good);  // HDOP 0.84

  // RMC saying "void" in the same epoch.
  const std::string rmc_void = line("GNRMC,104710.00,V,4832.5844943,N,00229.8320136,E,,,191022,,,N");
  EXPECT_FALSE(one_epoch(def, kHdt + rmc_void, kRtkFloat).good);

  // INS coasting without GNSS: quality 6.
  const std::string dr = line("GNGGA,104710.00,4832.5844943,N,00229.8320136,E,6,00,99.9,80.418,M,46.332,M,,");
  EXPECT_FALSE(one_epoch(def, kHdt, dr.substr(0, dr.size() - 2)).good);
  GnssConfig dr_ok = def;
  dr_ok.dead_reckoning_good = true;
  EXPECT_TRUE(one_epoch(dr_ok, kHdt, dr.substr(0, dr.size() - 2)).good);
}

TEST(GnssDriver, AnglesAndRatesByHand) {
  GnssConfig c = no_lever();
  c.require_heading = false;
  const std::string gga = kRtkFloat;
  auto heading_of = [&](double deg) {
    return one_epoch(c, line("GPHDT," + nmea::format_fixed(deg, 2) + ",T"), gga).heading;
  };
  EXPECT_NEAR(heading_of(0.0), std::numbers::pi / 2, 1e-12);     // north
  EXPECT_NEAR(heading_of(90.0), 0.0, 1e-12);                     // east
  EXPECT_NEAR(heading_of(180.0), -std::numbers::pi / 2, 1e-12);  // south
  EXPECT_NEAR(std::abs(heading_of(270.0)), std::numbers::pi, 1e-12);
  EXPECT_NEAR(heading_of(359.0), deg2rad(91.0), 1e-12);

  // 60°/min to starboard is 1°/s clockwise: ENU yaw rate -1°/s.
  GnssSample s = one_epoch(c, line("GPROT,60.0,A"), gga);
  EXPECT_TRUE(s.yaw_rate_valid);
  EXPECT_NEAR(s.yaw_rate, -deg2rad(1.0), 1e-12);
  s = one_epoch(c, line("GPROT,-30.0,A"), gga);
  EXPECT_NEAR(s.yaw_rate, deg2rad(0.5), 1e-12);
  EXPECT_FALSE(one_epoch(c, line("GPROT,-30.0,V"), gga).yaw_rate_valid);

  s = one_epoch(c, line("GPVTG,45.0,T,,M,19.438,N,36.0,K,A"), gga);
  EXPECT_TRUE(s.velocity_valid);
  EXPECT_NEAR(s.speed, 10.0, 1e-12);
  EXPECT_NEAR(s.course, deg2rad(45.0), 1e-12);
  s = one_epoch(c, line("GPVTG,135.0,T,,M,10.0,N,,K,A"), gga);
  EXPECT_NEAR(s.speed, 10.0 * 1852.0 / 3600.0, 1e-12);
  EXPECT_NEAR(s.course, deg2rad(-45.0), 1e-12);
  EXPECT_FALSE(one_epoch(c, line("GPVTG,135.0,T,,M,10.0,N,,K,N"), gga).velocity_valid);
  s = one_epoch(c, line("GNRMC,104710.00,A,4832.5844943,N,00229.8320136,E,20.0,270.0,191022,,,R"), gga);
  EXPECT_NEAR(s.speed, 20.0 * 1852.0 / 3600.0, 1e-12);
  EXPECT_NEAR(std::abs(s.course), std::numbers::pi, 1e-12);

  // PASHR: roll right side down +2°, pitch bow up +3° → ISO 8855 roll +2°, pitch -3° (nose up).
  s = one_epoch(c, line("PASHR,104710.000,10.00,T,+2.00,+3.00,+0.00,0.01,0.01,0.02,2,1"), gga);
  EXPECT_TRUE(s.attitude_valid);
  EXPECT_NEAR(s.roll, deg2rad(2.0), 1e-12);
  EXPECT_NEAR(s.pitch, deg2rad(-3.0), 1e-12);
  EXPECT_TRUE(s.heading_valid);
  EXPECT_NEAR(s.heading, deg2rad(80.0), 1e-12);
  // HDT wins over PASHR's heading.
  s = one_epoch(c, line("GPHDT,20.00,T") + line("PASHR,104710.000,10.00,T,+2.00,+3.00,+0.00,0.01,0.01,0.02,2,1"), gga);
  EXPECT_NEAR(s.heading, deg2rad(70.0), 1e-12);
}

GnssConfig lever_config(double x, double y, double z) {
  GnssConfig c;
  c.use_first_fix = false;
  c.origin_lat_deg = 48.0 + 32.5844943 / 60.0;  // the antenna position of kRtkFloat
  c.origin_lon_deg = 2.0 + 29.8320136 / 60.0;
  c.origin_height_m = 80.418 + 46.332;
  c.antenna_x = x;
  c.antenna_y = y;
  c.antenna_z = z;
  return c;
}

TEST(GnssDriver, LeverArmToRearAxle) {
  const GnssConfig c = lever_config(1.0, 0.0, 1.5);
  // Facing east: the rear axle is 1 m west of and 1.5 m below the antenna.
  Vec3 p = one_epoch(c, line("GPHDT,90.00,T"), kRtkFloat).enu;
  EXPECT_NEAR(p.x(), -1.0, 1e-6);
  EXPECT_NEAR(p.y(), 0.0, 1e-6);
  EXPECT_NEAR(p.z(), -1.5, 1e-6);
  // Facing north: 1 m south.
  p = one_epoch(c, line("GPHDT,0.00,T"), kRtkFloat).enu;
  EXPECT_NEAR(p.x(), 0.0, 1e-6);
  EXPECT_NEAR(p.y(), -1.0, 1e-6);
  // Facing east, nose 10° up: the forward offset rises (x sin10) and the mast tilts back (z sin10), so the
  // antenna is x cos10 - z sin10 ahead of and x sin10 + z cos10 above the rear axle.
  p = one_epoch(c, line("GPHDT,90.00,T") + line("PASHR,104710.00,90.00,T,+0.00,+10.00,,,,,4,1"), kRtkFloat).enu;
  const double t = deg2rad(10.0);
  EXPECT_NEAR(p.x(), -(std::cos(t) - 1.5 * std::sin(t)), 1e-6);
  EXPECT_NEAR(p.z(), -(std::sin(t) + 1.5 * std::cos(t)), 1e-6);
  // Facing north, rolled 5° right side down: an antenna 0.5 m to the left moves up and to the right.
  const GnssConfig left = lever_config(0.0, 0.5, 0.0);
  p = one_epoch(left, line("GPHDT,0.00,T") + line("PASHR,104710.00,0.00,T,+5.00,+0.00,,,,,4,1"), kRtkFloat).enu;
  const double r = deg2rad(5.0);
  EXPECT_NEAR(p.x(), 0.5 * std::cos(r), 1e-6);  // left of a car facing north is west: -x, removed: +x
  EXPECT_NEAR(p.z(), -0.5 * std::sin(r), 1e-6);
  // Without a heading only the height is removed, and the sample is not good.
  const GnssSample s = one_epoch(c, "", kRtkFloat);
  EXPECT_NEAR(s.enu.x(), 0.0, 1e-6);
  EXPECT_NEAR(s.enu.z(), -1.5, 1e-6);
  EXPECT_FALSE(s.good);
}

TEST(GnssDriver, OriginAtTheRearAxleOfTheFirstGoodFix) {
  GnssConfig c;
  c.antenna_x = 1.0;
  c.antenna_y = 0.0;
  c.antenna_z = 0.0;
  c.emit_on = "GGA";
  Harness h(c);
  h.feed(kHdt + kSingle + "\r\n", 0.0);  // single point: not good, no origin
  EXPECT_FALSE(h.driver.origin());
  h.feed(line("GPHDT,0.00,T") + kRtkFloat + "\r\n", 1.0);
  ASSERT_TRUE(h.driver.origin());
  ASSERT_EQ(h.samples.size(), 2u);
  EXPECT_FALSE(h.samples[0].good);
  EXPECT_TRUE(h.samples[1].good);
  EXPECT_NEAR(h.samples[1].enu.norm(), 0.0, 1e-6);
  // Facing north with the antenna 1 m ahead: the origin is 1 m south of the antenna, on a meridian of radius
  // M + h at the antenna's height.
  const double lat = 48.0 + 32.5844943 / 60.0;
  const Geodetic& o = h.driver.origin()->origin();
  EXPECT_NEAR(rad2deg(o.lat), lat - rad2deg(1.0 / (radii(lat).m + 80.418 + 46.332)), 1e-10);
  EXPECT_NEAR(rad2deg(o.lon), 2.0 + 29.8320136 / 60.0, 1e-10);
  EXPECT_NEAR(o.h, 80.418 + 46.332, 1e-6);
}

TEST(GnssDriver, RejectsUnknownConfigChoices) {
  GnssConfig c;
  c.min_fix = "rtk";
  EXPECT_THROW(GnssDriver(c, [](const GnssSample&) {}), std::invalid_argument);
  c = GnssConfig{};
  c.emit_on = "GSV";
  EXPECT_THROW(GnssDriver(c, [](const GnssSample&) {}), std::invalid_argument);
  c = GnssConfig{};
  c.max_line_length = -1;
  EXPECT_THROW(GnssDriver(c, [](const GnssSample&) {}), std::invalid_argument);
}

TEST(GnssDriver, ConfigSectionDeclaresEveryKeyWithItsDefault) {
  ConfigSchema schema;
  gnss_section().describe(schema);
  EXPECT_EQ(schema.entries().size(), 16u);  // one per GnssConfig member but the antenna (car.gnss_antenna)
  for (const auto& e : schema.entries()) {
    EXPECT_EQ(e.key.rfind("drivers.gnss.", 0), 0u) << e.key;
    EXPECT_FALSE(e.doc.empty()) << e.key;
  }
  const GnssConfig read = gnss_section().read(Config(std::make_shared<const ConfigSchema>(schema)));
  const GnssConfig def;
  EXPECT_EQ(read.min_fix, def.min_fix);
  EXPECT_EQ(read.emit_on, def.emit_on);
  EXPECT_EQ(read.max_hdop, def.max_hdop);
  EXPECT_EQ(read.antenna_z, def.antenna_z);
  EXPECT_EQ(read.use_first_fix, def.use_first_fix);
  EXPECT_EQ(read.device, "/dev/ttyGNSS");  // the udev symlink of deploy/99-fsd.rules
  EXPECT_EQ(read.baud, def.baud);
  ASSERT_NE(schema.find("drivers.gnss.max_hdop"), nullptr);
  EXPECT_TRUE(schema.find("drivers.gnss.max_hdop")->tunable);
}

}  // namespace
}  // namespace fsd
