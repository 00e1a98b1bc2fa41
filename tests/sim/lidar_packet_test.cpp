// The VLP-16 model's packets against the manual's layout and timing, read directly with vlp16_format.hpp.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "common/wire/vlp16_format.hpp"
#include "drivers/sim/sensors/lidar_model.hpp"
#include "tests/sim/world_test_util.hpp"

namespace fsd::sim {
namespace {

namespace vlp = wire::vlp16;
using test::bare_config;
using test::make_cone;
using test::make_track;

struct Captured {
  std::vector<Stamp> stamps;
  std::vector<std::vector<std::uint8_t>> packets;
};

Pose3 standing_still(Stamp) { return Pose3::Identity(); }

Captured run(const LidarConfig& cfg, const World& world, std::uint64_t seed, Stamp until, Stamp start = 0.0,
             int steps = 1) {
  Captured c;
  LidarModel lidar(cfg, world, seed, start);
  for (int i = 1; i <= steps; ++i)
    lidar.advance_to(start + until * i / steps, standing_still, [&](Stamp t, std::span<const std::uint8_t> b) {
      c.stamps.push_back(t);
      c.packets.emplace_back(b.begin(), b.end());
    });
  EXPECT_EQ(lidar.packets_sent(), c.packets.size());
  return c;
}

double azimuth_deg(const std::vector<std::uint8_t>& p, std::size_t block) {
  return vlp::read_u16(p, block * vlp::kBlockSize + 2) * 0.01;
}

class LidarPackets : public ::testing::Test {
 protected:
  World world{make_track({make_cone(6.0, 1.0), make_cone(5.0, -2.0, ConeRole::Right)}), bare_config(), 1};
};

TEST_F(LidarPackets, LayoutFlagsAndFactoryBytes) {
  const auto c = run(LidarConfig{}, world, 1, 0.2);
  ASSERT_FALSE(c.packets.empty());
  for (const auto& p : c.packets) {
    ASSERT_EQ(p.size(), 1206u);
    for (std::size_t b = 0; b < 12; ++b) {
      EXPECT_EQ(p[b * 100], 0xFF);
      EXPECT_EQ(p[b * 100 + 1], 0xEE);
      EXPECT_LT(vlp::read_u16(p, b * 100 + 2), 36000);
    }
    EXPECT_EQ(p[1204], 0x37);
    EXPECT_EQ(p[1205], 0x22);
  }
  LidarConfig other;
  other.return_mode = "last";
  other.product_id = 0x21;
  const auto o = run(other, world, 1, 0.01);
  ASSERT_FALSE(o.packets.empty());
  EXPECT_EQ(o.packets[0][1204], 0x38);
  EXPECT_EQ(o.packets[0][1205], 0x21);
}

TEST_F(LidarPackets, AzimuthAdvancesByTheFiringTimeAtTheRotationRate) {
  for (double hz : {10.0, 20.0, 5.0}) {
    LidarConfig cfg;
    cfg.rotation_hz = hz;
    const auto c = run(cfg, world, 1, 0.3);
    // One block is two firing sequences: 2 × 55.296 µs × 360° × f (0.19907° per sequence at 10 Hz).
    const double per_block = 360.0 * hz * 110.592e-6;
    double prev = azimuth_deg(c.packets[0], 0);
    EXPECT_NEAR(prev, 0.0, 0.006);  // the head points along +x at the start
    int checked = 0;
    for (const auto& p : c.packets)
      for (std::size_t b = 0; b < 12; ++b) {
        const double a = azimuth_deg(p, b);
        if (&p == &c.packets[0] && b == 0) continue;
        const double step = std::fmod(a - prev + 360.0, 360.0);
        EXPECT_NEAR(step, per_block, 0.0101) << hz << " Hz";
        prev = a;
        ++checked;
      }
    EXPECT_GT(checked, 2000);
  }
  EXPECT_NEAR(360.0 * 10.0 * 55.296e-6, 0.2, 0.001);  // the 0.2° of the datasheet
}

TEST_F(LidarPackets, PacketRateIs754PerSecondAtAnyRotationRate) {
  for (double hz : {5.0, 10.0, 20.0}) {
    LidarConfig cfg;
    cfg.rotation_hz = hz;
    const auto c = run(cfg, world, 1, 4.0, 0.0, 40);
    const double rate = static_cast<double>(c.packets.size()) / 4.0;
    EXPECT_NEAR(rate, 754.0, 7.54) << hz << " Hz";
  }
}

TEST_F(LidarPackets, TimestampsAreMicrosecondsPastTheHourOfTheFirstFiring) {
  LidarConfig cfg;
  cfg.latency = 0.002;
  const Stamp start = 2 * 3600.0 - 0.05;  // 50 ms before the top of an hour
  const auto c = run(cfg, world, 1, 0.1, start);
  ASSERT_GT(c.packets.size(), 70u);
  bool wrapped = false;
  for (std::size_t n = 0; n < c.packets.size(); ++n) {
    const double first_firing = start + n * 1327.104e-6;
    const double past_hour = first_firing >= 7200.0 ? first_firing - 7200.0 : first_firing - 3600.0;
    EXPECT_NEAR(vlp::read_u32(c.packets[n], 1200), past_hour * 1e6, 0.51) << n;
    wrapped = wrapped || first_firing >= 7200.0;
    // Leaves the sensor after its last firing, plus the latency.
    EXPECT_NEAR(c.stamps[n], first_firing + 1327.104e-6 + 0.002, 1e-9);
  }
  EXPECT_TRUE(wrapped);
}

TEST_F(LidarPackets, EmitsOnlyCompletePackets) {
  LidarModel lidar(LidarConfig{}, world, 1);
  int n = 0;
  const ByteSink count = [&](Stamp, std::span<const std::uint8_t>) { ++n; };
  lidar.advance_to(0.0013, standing_still, count);  // one packet takes 1.327 ms
  EXPECT_EQ(n, 0);
  lidar.advance_to(0.00133, standing_still, count);
  EXPECT_EQ(n, 1);
  lidar.advance_to(0.0005, standing_still, count);  // going back in time emits nothing
  EXPECT_EQ(n, 1);
}

TEST_F(LidarPackets, DeterministicForASeedWhateverTheStepping) {
  const auto a = run(LidarConfig{}, world, 5, 0.3, 0.0, 1);
  const auto b = run(LidarConfig{}, world, 5, 0.3, 0.0, 97);
  const auto c = run(LidarConfig{}, world, 6, 0.3, 0.0, 1);
  ASSERT_EQ(a.packets.size(), b.packets.size());
  EXPECT_EQ(a.packets, b.packets);
  EXPECT_EQ(a.stamps, b.stamps);
  ASSERT_EQ(a.packets.size(), c.packets.size());
  EXPECT_NE(a.packets, c.packets);  // other noise
}

TEST_F(LidarPackets, DropoutLosesThatShareOfReturns) {
  LidarConfig none, some;
  some.dropout = 0.3;
  const auto a = run(none, world, 3, 0.5);
  const auto b = run(some, world, 3, 0.5);
  ASSERT_EQ(a.packets.size(), b.packets.size());
  double returns = 0, kept = 0;
  for (std::size_t n = 0; n < a.packets.size(); ++n)
    for (std::size_t blk = 0; blk < 12; ++blk)
      for (std::size_t s = 0; s < 2; ++s)
        for (std::size_t k = 0; k < 16; ++k) {
          const auto at = vlp::channel_offset(blk, s, k);
          if (vlp::read_u16(a.packets[n], at) == 0) continue;
          ++returns;
          kept += vlp::read_u16(b.packets[n], at) != 0;
        }
  ASSERT_GT(returns, 10000);
  EXPECT_NEAR(1.0 - kept / returns, 0.3, 0.01);
}

}  // namespace
}  // namespace fsd::sim
