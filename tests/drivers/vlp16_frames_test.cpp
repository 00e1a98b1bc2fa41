// Frames from a stream of VLP-16 packets: cut angle, whole revolutions, times on the stack clock, robustness to
// reordering and a stopped motor; and the mapping of sensor timestamps onto the stack clock.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "drivers/vlp16/frame_assembler.hpp"
#include "drivers/vlp16/scan_builder.hpp"
#include "drivers/vlp16/sensor_clock.hpp"
#include "tests/drivers/vlp16_test_packets.hpp"

namespace fsd {
namespace {

using test::Vlp16PacketBytes;

constexpr double kPacketUs = 12 * 110.592;  // single return: 12 firings per packet
constexpr int kStep = 20;                   // 0.20° per firing → 1800 firings = 150 packets per revolution
constexpr std::size_t kPointsPerRevolution = 1800 * 32;

// Packet k of a sensor spinning from `start_counts` at 0.20° per firing; every channel returns 10 m.
struct Stream {
  int start_counts = 0;
  std::uint32_t t0_us = 1'000'000;
  std::uint32_t timestamp(int k) const { return t0_us + static_cast<std::uint32_t>(std::lround(k * kPacketUs)); }
  std::vector<std::uint8_t> packet(int k) const {
    Vlp16PacketBytes p(timestamp(k), (start_counts + k * 12 * kStep) % 36000, kStep);
    p.fill(5000);
    return p.bytes();
  }
  // Lockstep receive time: the moment the packet's firings end, on a stack clock equal to sensor time.
  Stamp receive(int k) const { return (timestamp(k) + kPacketUs) * 1e-6; }
};

struct Collected {
  std::vector<Scan> scans;
  FrameAssembler::ScanHandler handler() {
    return [this](Scan&& s) { scans.push_back(std::move(s)); };
  }
};

Vlp16Config config_with_cut(double cut_deg) {
  Vlp16Config c;
  c.frame_cut_deg = cut_deg;
  return c;
}

double deg(float rad) { return rad * 180.0 / 3.14159265358979323846; }

TEST(Vlp16Frames, EachFrameIsOneRevolutionFromTheCutAngle) {
  // Cut at 0.06°: inside the firing at 0.00°, whose lasers 0..14 of sequence 0 (azimuth 0.20° × slot × 2.304 /
  // 110.592 < 0.06°) end the frame and the rest start the next one.
  Collected got;
  Vlp16ScanBuilder builder(config_with_cut(0.06), got.handler());
  const Stream s{10000};  // starts at 100°: the first frame is partial
  for (int k = 0; k < 500; ++k) builder.on_data_packet(s.receive(k), s.packet(k));
  builder.flush();

  ASSERT_EQ(got.scans.size(), 4u);
  // 100.00° .. 0.06°: 1300 firings of 32 returns, plus 15 of the firing at 0.00°.
  EXPECT_EQ(got.scans[0].points.size(), 1300u * 32u + 15u);
  for (std::size_t i = 1; i < 3; ++i) {
    const auto& pts = got.scans[i].points;
    ASSERT_EQ(pts.size(), kPointsPerRevolution) << "frame " << i;
    EXPECT_NEAR(deg(pts.front().azimuth), 0.0625, 1e-5);                     // laser 15 of the 0.00° firing
    EXPECT_NEAR(deg(pts.back().azimuth), 0.2 * 14 * 2.304 / 110.592, 1e-5);  // laser 14, 0.0583°
    EXPECT_EQ(got.scans[i].seq, i);
  }
  // 6000 firings in all.
  std::size_t total = 0;
  for (const auto& scan : got.scans) total += scan.points.size();
  EXPECT_EQ(total, 500u * 384u);
  EXPECT_EQ(builder.frames(), 4u);
}

TEST(Vlp16Frames, PointTimesAreTheFiringTimesOnTheStackClock) {
  Collected got;
  Vlp16ScanBuilder builder(config_with_cut(90.0), got.handler());
  const Stream s{0};
  for (int k = 0; k < 200; ++k) builder.on_data_packet(s.receive(k), s.packet(k));
  ASSERT_GE(got.scans.size(), 2u);

  // With the receive time at the end of each packet's firings, firing times come out exactly: the first firing
  // at 90.00° is firing 450 = packet 37, block 6.
  const Scan& frame = got.scans[1];
  const double expected_start = (s.timestamp(37) + 6 * 110.592) * 1e-6;
  EXPECT_NEAR(frame.stamp, expected_start, 1e-9);
  EXPECT_NEAR(frame.points.front().t, expected_start, 1e-9);
  // Laser 9 of sequence 1 of that firing: + 55.296 + 9 × 2.304 µs.
  EXPECT_NEAR(frame.points[16 + 9].t, expected_start + (55.296 + 9 * 2.304) * 1e-6, 1e-9);
  EXPECT_EQ(frame.points[16 + 9].ring, 12);  // laser 9 is +9°
  EXPECT_NEAR(frame.points[16 + 9].distance, 10.0f, 1e-6);
  EXPECT_EQ(frame.points[16 + 9].intensity, 9.0f);
  for (std::size_t i = 1; i < frame.points.size(); ++i) ASSERT_GE(frame.points[i].t, frame.points[i - 1].t);
  // The revolution ends with firing 2249 = packet 187, block 5, laser 15 of sequence 1. (Timestamps are whole
  // µs, so this is not exactly 1799 × 110.592 µs after the start.)
  EXPECT_NEAR(frame.points.back().t, (s.timestamp(187) + 5 * 110.592 + 55.296 + 15 * 2.304) * 1e-6, 1e-9);
}

TEST(Vlp16Frames, ReorderedPacketAtTheCutMakesNoSliverFrame) {
  Collected straight, reordered;
  Vlp16ScanBuilder a(config_with_cut(0.0), straight.handler());
  Vlp16ScanBuilder b(config_with_cut(0.0), reordered.handler());
  const Stream s{30000};  // 300°: packet 25 starts at 0.00°
  for (int k = 0; k < 120; ++k) {
    a.on_data_packet(s.receive(k), s.packet(k));
    b.on_data_packet(s.receive(k), s.packet(k));
    if (k == 25) b.on_data_packet(s.receive(24), s.packet(24));  // 357.6° .. 359.8° arrives again, late
  }
  a.flush();
  b.flush();
  ASSERT_EQ(straight.scans.size(), 2u);
  ASSERT_EQ(reordered.scans.size(), 2u);
  EXPECT_EQ(reordered.scans[1].points.size(), straight.scans[1].points.size() + 384u);
}

TEST(Vlp16Frames, StreamStartingJustAfterTheCutIsNotCutAtOnce) {
  Collected got;
  Vlp16ScanBuilder builder(config_with_cut(0.0), got.handler());
  const Stream s{1000};  // 10°
  for (int k = 0; k < 150; ++k) builder.on_data_packet(s.receive(k), s.packet(k));
  ASSERT_EQ(got.scans.size(), 1u);  // cut once, at 360°
  EXPECT_EQ(got.scans[0].points.size(), 1750u * 32u);
}

TEST(Vlp16Frames, StoppedMotorIsCutByPointCount) {
  Collected got;
  FrameAssembler frames(0.0, 1000);
  PacketDecoder decoder(LaserTable::builtin(), 0.5, 130);
  Vlp16PacketBytes p(0, 4500, 0);  // every block at 45°
  p.fill(5000);
  std::vector<Vlp16Return> returns;
  ASSERT_EQ(decoder.decode(p.bytes(), returns), PacketStatus::Ok);
  for (int k = 0; k < 10; ++k) frames.add(k * 0.001, returns, got.handler());
  frames.flush(got.handler());
  ASSERT_EQ(got.scans.size(), 4u);
  EXPECT_EQ(got.scans[0].points.size(), 1000u);
  EXPECT_EQ(got.scans[3].points.size(), 840u);
  EXPECT_EQ(frames.forced_cuts(), 3u);
}

TEST(Vlp16Frames, LostPacketsAreEstimatedFromTimestamps) {
  Collected got;
  Vlp16ScanBuilder builder(config_with_cut(0.0), got.handler());
  const Stream s{0};
  for (int k : {0, 1, 2, 5, 6}) builder.on_data_packet(s.receive(k), s.packet(k));
  EXPECT_EQ(builder.lost_packets(), 2u);
}

// --- SensorClock ---------------------------------------------------------------------------------------------

TEST(Vlp16SensorClock, ExactWithoutLatency) {
  SensorClock clock;
  for (int k = 0; k < 100; ++k) {
    const std::uint32_t ts = 500'000'000u + static_cast<std::uint32_t>(k * 1327);
    const Stamp receive = 42.0 + (ts + kPacketUs) * 1e-6;  // stack clock 42 s ahead of the sensor
    EXPECT_NEAR(clock.packet_start(receive, ts, kPacketUs), 42.0 + ts * 1e-6, 1e-9);
  }
  EXPECT_EQ(clock.resets(), 1u);
}

TEST(Vlp16SensorClock, RejectsReceiveJitter) {
  SensorClock clock;
  std::uint32_t lcg = 12345;
  const double base_latency = 300e-6;
  double naive_worst = 0, mapped_worst = 0;
  for (int k = 0; k < 2000; ++k) {
    lcg = lcg * 1664525u + 1013904223u;
    // Scheduling jitter up to 4 ms; every 20th packet arrives with the bare network latency.
    const double jitter = k % 20 == 0 ? 0.0 : (lcg >> 8) / double(1 << 24) * 4e-3;
    const std::uint32_t ts = static_cast<std::uint32_t>(std::lround(k * kPacketUs));
    const double truth = ts * 1e-6;
    const Stamp receive = truth + kPacketUs * 1e-6 + base_latency + jitter;
    const Stamp mapped = clock.packet_start(receive, ts, kPacketUs);
    naive_worst = std::max(naive_worst, std::abs(receive - kPacketUs * 1e-6 - truth - base_latency));
    mapped_worst = std::max(mapped_worst, std::abs(mapped - truth - base_latency));
  }
  EXPECT_GT(naive_worst, 3e-3);
  // Between two jitter-free packets (26.5 ms) the estimate may rise by max_drift × 26.5 ms = 5.3 µs.
  EXPECT_LT(mapped_worst, 6e-6);
}

TEST(Vlp16SensorClock, FollowsCrystalDrift) {
  SensorClock clock;  // sensor crystal 100 ppm slow against the host
  double worst = 0;
  for (int k = 0; k < 7540; ++k) {  // 10 s
    const double host_start = k * kPacketUs * 1e-6;
    const auto ts = static_cast<std::uint32_t>(std::lround(host_start * (1 - 1e-4) * 1e6));
    const Stamp mapped = clock.packet_start(host_start + kPacketUs * 1e-6, ts, kPacketUs);
    worst = std::max(worst, std::abs(mapped - host_start));
  }
  EXPECT_LT(worst, 2e-6);
}

TEST(Vlp16SensorClock, UnwrapsTheHour) {
  SensorClock clock;
  const std::uint32_t hour = 3'600'000'000u;
  Stamp previous = 0;
  for (int k = 0; k < 10; ++k) {
    const std::uint64_t sensor = hour - 5000 + static_cast<std::uint64_t>(k * 1327);
    const Stamp receive = 100.0 + sensor * 1e-6 + kPacketUs * 1e-6;
    const Stamp start = clock.packet_start(receive, static_cast<std::uint32_t>(sensor % hour), kPacketUs);
    EXPECT_NEAR(start, 100.0 + sensor * 1e-6, 1e-6);
    if (k > 0) {
      EXPECT_NEAR(start - previous, 1327e-6, 1e-9);
    }
    previous = start;
  }
  EXPECT_EQ(clock.hour_wraps(), 1u);
}

TEST(Vlp16SensorClock, RecoversFromAClockStep) {
  SensorClock clock;
  int k = 0;
  const auto feed = [&](std::int64_t sensor_shift_us) {
    const double host = k * kPacketUs * 1e-6;
    ++k;
    const auto ts = static_cast<std::uint32_t>(std::lround(host * 1e6) + 1'000'000'000 + sensor_shift_us);
    return clock.packet_start(host + kPacketUs * 1e-6, ts, kPacketUs) - host;  // error of the mapping
  };
  for (int i = 0; i < 10; ++i) EXPECT_NEAR(feed(0), 0.0, 1e-6);
  // The sensor's clock steps back by 10 s (e.g. on PPS lock): held for a few packets, then re-estimated.
  int wrong = 0;
  for (int i = 0; i < 20; ++i) {
    if (std::abs(feed(-10'000'000)) > 1e-6) ++wrong;
  }
  EXPECT_EQ(wrong, SensorClock::Params{}.jump_confirmations - 1);
  EXPECT_EQ(clock.resets(), 2u);
  // A forward step is taken at once (the minimum follows it).
  EXPECT_NEAR(feed(+5'000'000), 0.0, 1e-6);
}

}  // namespace
}  // namespace fsd
