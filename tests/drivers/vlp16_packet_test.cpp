// VLP-16 data packets built byte by byte: geometry conventions, azimuth interpolation, firing times, dual
// return, product ids, validation. Expected values come from the manual's formulas evaluated here.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "common/wire/vlp16_format.hpp"
#include "drivers/vlp16/decoder.hpp"
#include "tests/drivers/vlp16_test_packets.hpp"

namespace fsd {
namespace {

using test::Vlp16PacketBytes;

double rad(double deg) { return deg * std::numbers::pi / 180.0; }

PacketDecoder make_decoder() { return PacketDecoder(LaserTable::builtin(), 0.5, 130.0); }

std::vector<Vlp16Return> decode_ok(PacketDecoder& d, std::vector<std::uint8_t>& bytes) {
  std::vector<Vlp16Return> out;
  EXPECT_EQ(d.decode(bytes, out), PacketStatus::Ok);
  return out;
}

// Sensor-frame point of the VLP-16 manual with the ROS axes: x = d cosω cosα, y = -d cosω sinα, z = d sinω + off.
void expect_point(const Vlp16Return& r, double d, double elevation_deg, double offset, double azimuth_deg) {
  EXPECT_NEAR(r.azimuth_deg, azimuth_deg, 1e-9);
  EXPECT_NEAR(r.distance_m, d, 1e-12);
  EXPECT_NEAR(r.x, d * std::cos(rad(elevation_deg)) * std::cos(rad(azimuth_deg)), 1e-9);
  EXPECT_NEAR(r.y, -d * std::cos(rad(elevation_deg)) * std::sin(rad(azimuth_deg)), 1e-9);
  EXPECT_NEAR(r.z, d * std::sin(rad(elevation_deg)) + offset, 1e-9);
}

TEST(Vlp16Packet, AxesFollowTheRosConvention) {
  auto d = make_decoder();
  // Laser 0 (-15°) straight ahead at azimuth 0: 10 m (5000 × 2 mm), reflectivity 77.
  Vlp16PacketBytes ahead(1000, 0, 20);
  ahead.channel(0, 0, 0, 5000, 77);
  const auto a = decode_ok(d, ahead.bytes());
  ASSERT_EQ(a.size(), 1u);
  EXPECT_NEAR(a[0].x, 10 * std::cos(rad(15)), 1e-9);  // 9.659 m forward
  EXPECT_NEAR(a[0].y, 0.0, 1e-12);
  EXPECT_NEAR(a[0].z, -10 * std::sin(rad(15)) + 0.0112, 1e-9);  // below, plus the manual's +11.2 mm offset
  EXPECT_EQ(a[0].intensity, 77);
  EXPECT_EQ(a[0].laser, 0);
  EXPECT_EQ(a[0].ring, 0);

  // Azimuth 90° is clockwise seen from above, i.e. to the right: negative y. Laser 1 (+1°), 5 m.
  Vlp16PacketBytes right(1000, 9000, 20);
  right.channel(0, 0, 1, 2500, 5);
  const auto r = decode_ok(d, right.bytes());
  ASSERT_EQ(r.size(), 1u);
  // Laser 1 fires 2.304 µs into the block, 0.20° × 2.304 / 110.592 later in azimuth.
  expect_point(r[0], 5.0, 1, -0.0007, 90.0 + 0.20 * 2.304 / 110.592);
  EXPECT_NEAR(r[0].x, 0.0, 5e-4);
  EXPECT_NEAR(r[0].y, -5 * std::cos(rad(1)), 1e-6);
  EXPECT_EQ(r[0].ring, 8);  // +1° is the ninth beam from the bottom
}

TEST(Vlp16Packet, InterpolatesAzimuthPerSequenceAndLaserAndTimesEachFiring) {
  auto d = make_decoder();
  // Blocks at 120.00°, 120.40°, ... (40 counts per block); block 11 moved to 124.50° so the last block's step
  // (50 counts, from block 10 at 124.00°) differs from the others.
  Vlp16PacketBytes p(5000, 12000, 40);
  p.azimuth(11, 12450);
  p.channel(5, 1, 7, 1500, 9);    // block 5, second sequence, laser 7 (+7°)
  p.channel(11, 1, 15, 2000, 3);  // last block, second sequence, laser 15 (+15°)
  p.channel(0, 0, 0, 1000, 1);    // first firing of the packet
  const auto out = decode_ok(d, p.bytes());
  ASSERT_EQ(out.size(), 3u);

  // Emitted in firing order.
  EXPECT_EQ(out[0].laser, 0);
  EXPECT_DOUBLE_EQ(out[0].t_us, 5000.0);
  expect_point(out[0], 2.0, -15, 0.0112, 120.0);

  // Block 5 fires at 5 × 110.592; sequence 1 at +55.296; laser 7 at +7 × 2.304 → offset 624.384 µs.
  // Azimuth 122.00° + 0.40° × (55.296 + 16.128) / 110.592 = 122.00° + 0.40° × 0.6458333 = 122.2583333°.
  EXPECT_EQ(out[1].laser, 7);
  EXPECT_NEAR(out[1].firing_offset_us, 624.384, 1e-9);
  EXPECT_NEAR(out[1].t_us, 5624.384, 1e-9);
  expect_point(out[1], 3.0, 7, -0.0051, 122.0 + 0.40 * 0.64583333333333333);

  // Block 11: 11 × 110.592 + 55.296 + 15 × 2.304 = 1306.368 µs; azimuth 124.50° + 0.50° × 0.8125 = 124.90625°.
  EXPECT_EQ(out[2].laser, 15);
  EXPECT_NEAR(out[2].t_us, 5000 + 1306.368, 1e-9);
  expect_point(out[2], 4.0, 15, -0.0112, 124.90625);
}

TEST(Vlp16Packet, WrapsAzimuthAt360) {
  auto d = make_decoder();
  // Blocks at 359.50, 359.70, 359.90, 0.10, ... : the step across the wrap is 20 counts, not -35980.
  Vlp16PacketBytes p(0, 35950, 20);
  p.channel(2, 0, 0, 1000, 1);   // 359.90° exactly
  p.channel(2, 1, 15, 1000, 1);  // 359.90° + 0.20° × 0.8125 = 360.0625° → 0.0625°
  const auto out = decode_ok(d, p.bytes());
  ASSERT_EQ(out.size(), 2u);
  expect_point(out[0], 2.0, -15, 0.0112, 359.90);
  expect_point(out[1], 2.0, 15, -0.0112, 0.0625);
  EXPECT_LT(out[1].y, 0.0);  // just right of the x axis

  // 359.99° → 0.19°: block 1 at 35999, block 2 at 19.
  Vlp16PacketBytes q(0, 35979, 20);
  q.channel(1, 0, 8, 1000, 1);  // 359.99° + 0.20° × 8 × 2.304 / 110.592 = 360.02333° → 0.0233°
  q.channel(1, 1, 0, 1000, 1);  // 359.99° + 0.20° × 0.5 = 0.09°
  const auto w = decode_ok(d, q.bytes());
  ASSERT_EQ(w.size(), 2u);
  EXPECT_NEAR(w[0].azimuth_deg, 359.99 + 0.20 * 8 * 2.304 / 110.592 - 360.0, 1e-9);
  EXPECT_NEAR(w[1].azimuth_deg, 0.09, 1e-9);
  for (const auto& r : w) {
    EXPECT_GE(r.azimuth_deg, 0.0);
    EXPECT_LT(r.azimuth_deg, 360.0);
  }
}

TEST(Vlp16Packet, DualReturnEmitsEachEchoOnce) {
  auto d = make_decoder();
  // Pairs of blocks at 10.00°, 10.40°, ...; pair 1 = blocks 2 (last echo) and 3 (strongest echo).
  auto p = Vlp16PacketBytes::dual(2000, 1000, 40);
  p.channel(2, 0, 0, 2000, 10).channel(3, 0, 0, 3000, 200);  // two different echoes
  p.channel(2, 0, 1, 2500, 50).channel(3, 0, 1, 2500, 50);   // the same echo twice
  p.channel(2, 1, 4, 1500, 20);                              // last echo only
  // Last pair (blocks 10, 11) at 12.50°: 90 counts after pair 4 (11.60°), reused as its own step.
  p.azimuth(10, 1250).azimuth(11, 1250);
  p.channel(11, 1, 0, 1000, 7);
  const auto out = decode_ok(d, p.bytes());
  ASSERT_EQ(out.size(), 5u);

  // Pair 1 fires at 1 × 110.592 µs: both blocks of a pair are the same firing.
  EXPECT_EQ(out[0].kind, ReturnKind::Last);
  EXPECT_EQ(out[1].kind, ReturnKind::Strongest);
  EXPECT_EQ(out[0].laser, 0);
  EXPECT_EQ(out[1].laser, 0);
  expect_point(out[0], 4.0, -15, 0.0112, 10.40);
  expect_point(out[1], 6.0, -15, 0.0112, 10.40);
  EXPECT_DOUBLE_EQ(out[0].t_us, 2000 + 110.592);
  EXPECT_DOUBLE_EQ(out[1].t_us, 2000 + 110.592);
  EXPECT_EQ(out[1].intensity, 200);

  EXPECT_EQ(out[2].kind, ReturnKind::StrongestAndLast);
  EXPECT_EQ(out[2].laser, 1);
  EXPECT_EQ(d.counters().dual_duplicates, 1u);

  // Laser 4, sequence 1: 10.40° + 0.40° × (55.296 + 9.216) / 110.592.
  EXPECT_EQ(out[3].kind, ReturnKind::Last);
  EXPECT_EQ(out[3].laser, 4);
  EXPECT_NEAR(out[3].azimuth_deg, 10.40 + 0.40 * 64.512 / 110.592, 1e-9);
  EXPECT_NEAR(out[3].t_us, 2000 + 110.592 + 64.512, 1e-9);

  // Pair 5 fires at 5 × 110.592; azimuth 12.50° + 0.90° × 0.5.
  EXPECT_EQ(out[4].kind, ReturnKind::Strongest);
  EXPECT_NEAR(out[4].azimuth_deg, 12.95, 1e-9);
  EXPECT_NEAR(out[4].t_us, 2000 + 5 * 110.592 + 55.296, 1e-9);

  PacketHeader h;
  ASSERT_EQ(PacketDecoder::check(p.bytes(), h), PacketStatus::Ok);
  EXPECT_TRUE(h.dual());
  EXPECT_DOUBLE_EQ(h.duration_us(), 6 * 110.592);
}

TEST(Vlp16Packet, SingleReturnModesAndProducts) {
  auto d = make_decoder();
  Vlp16PacketBytes last(0, 0, 20, 0x38, 0x22);
  last.channel(0, 0, 0, 1000, 1);
  const auto l = decode_ok(d, last.bytes());
  ASSERT_EQ(l.size(), 1u);
  EXPECT_EQ(l[0].kind, ReturnKind::Last);

  Vlp16PacketBytes early(0, 0, 20, 0x37, 0x21);  // early firmware reports the HDL-32E id
  early.channel(0, 0, 0, 1000, 1);
  const auto e = decode_ok(d, early.bytes());
  ASSERT_EQ(e.size(), 1u);
  EXPECT_EQ(e[0].kind, ReturnKind::Strongest);

  std::vector<Vlp16Return> out;
  Vlp16PacketBytes vlp32(0, 0, 20, 0x37, 0x28);  // VLP-32C: other elevations, must not be read as a VLP-16
  EXPECT_EQ(d.decode(vlp32.bytes(), out), PacketStatus::UnknownProduct);
  EXPECT_EQ(d.counters().packets, 2u);
}

TEST(Vlp16Packet, RejectsAndCountsMalformedPackets) {
  auto d = make_decoder();
  std::vector<Vlp16Return> out;
  const auto good = [] {
    Vlp16PacketBytes p(0, 0, 20);
    p.fill(1000);
    return p.bytes();
  };

  auto shorter = good();
  shorter.pop_back();
  auto longer = good();
  longer.push_back(0);
  EXPECT_EQ(d.decode(shorter, out), PacketStatus::WrongSize);
  EXPECT_EQ(d.decode(longer, out), PacketStatus::WrongSize);
  EXPECT_EQ(d.decode(std::span<const std::uint8_t>(), out), PacketStatus::WrongSize);

  auto flag = good();
  flag[7 * 100 + 1] = 0xDD;  // block 7: FF DD instead of FF EE (an HDL-32E lower block, say)
  EXPECT_EQ(d.decode(flag, out), PacketStatus::BadFlag);

  auto azimuth = good();
  azimuth[3 * 100 + 2] = 0xA0;  // 36000 = 0x8CA0
  azimuth[3 * 100 + 3] = 0x8C;
  EXPECT_EQ(d.decode(azimuth, out), PacketStatus::BadAzimuth);

  auto mode = good();
  mode[1204] = 0x40;
  EXPECT_EQ(d.decode(mode, out), PacketStatus::UnknownReturnMode);

  auto product = good();
  product[1205] = 0x00;
  EXPECT_EQ(d.decode(product, out), PacketStatus::UnknownProduct);

  EXPECT_TRUE(out.empty());  // nothing of a rejected packet leaks out
  const auto& c = d.counters();
  EXPECT_EQ(c.wrong_size, 3u);
  EXPECT_EQ(c.bad_flag, 1u);
  EXPECT_EQ(c.bad_azimuth, 1u);
  EXPECT_EQ(c.unknown_return_mode, 1u);
  EXPECT_EQ(c.unknown_product, 1u);
  EXPECT_EQ(c.rejected(), 7u);
  EXPECT_EQ(c.packets, 0u);

  auto ok = good();
  EXPECT_EQ(d.decode(ok, out), PacketStatus::Ok);  // and it keeps going
  EXPECT_EQ(out.size(), 12u * 32u);
  EXPECT_EQ(d.counters().returns, 384u);
}

TEST(Vlp16Packet, RangeFilterAndMissingReturns) {
  PacketDecoder d(LaserTable::builtin(), 0.5, 130.0);
  Vlp16PacketBytes p(0, 0, 20);
  p.channel(0, 0, 0, 100, 1);    // 0.2 m: inside the blind zone
  p.channel(0, 0, 2, 250, 1);    // 0.5 m: kept (bounds inclusive)
  p.channel(0, 0, 4, 65000, 1);  // 130.0 m: kept
  p.channel(0, 0, 6, 65535, 1);  // 131.07 m: too far
  const auto out = decode_ok(d, p.bytes());
  ASSERT_EQ(out.size(), 2u);
  EXPECT_EQ(out[0].laser, 2);
  EXPECT_EQ(out[1].laser, 4);
  EXPECT_EQ(d.counters().out_of_range, 2u);
  EXPECT_EQ(d.counters().no_return, 384u - 4u);

  EXPECT_THROW(PacketDecoder(LaserTable::builtin(), 5.0, 5.0), std::invalid_argument);
  EXPECT_THROW(PacketDecoder(LaserTable::builtin(), -1.0, 5.0), std::invalid_argument);
}

}  // namespace
}  // namespace fsd
