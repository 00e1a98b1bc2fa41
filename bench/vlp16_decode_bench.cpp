// VLP-16 decode rate on one core (goal: ≥ 200 × the sensor's 754 packets/s). Run from the worktree root so the
// recorded capture is found:  build/bench/vlp16_decode_bench
// items_per_second = packets decoded per second; "x_sensor" = that rate / 754 packets/s.
#include <benchmark/benchmark.h>

#include <cstdint>
#include <cstdio>
#include <vector>

#include "common/wire/vlp16_format.hpp"
#include "drivers/vlp16/decoder.hpp"
#include "drivers/vlp16/pcap_reader.hpp"
#include "drivers/vlp16/scan_builder.hpp"

namespace {

using Packet = std::vector<std::uint8_t>;
constexpr double kSensorPacketsPerSecond = 754.0;

std::vector<Packet> recorded_packets() {
  std::vector<Packet> out;
  try {
    fsd::PcapReader reader("../shared/data/vlp16/velodyne_vlp16.pcap", {2368});
    fsd::UdpDatagram d;
    while (reader.next(d)) out.emplace_back(d.payload.begin(), d.payload.end());
  } catch (const fsd::PcapError& e) {
    std::fprintf(stderr, "%s (run from the worktree root)\n", e.what());
  }
  return out;
}

// Every channel returns (the worst case for the decoder): 384 returns per packet, or 768 blocks' worth in dual.
Packet full_packet(std::uint8_t mode) {
  namespace w = fsd::wire::vlp16;
  Packet p(w::kPacketSize, 0);
  for (std::size_t b = 0; b < w::kBlocks; ++b) {
    p[b * w::kBlockSize] = w::kFlag0;
    p[b * w::kBlockSize + 1] = w::kFlag1;
    const std::size_t firing = mode == w::kReturnDual ? b / 2 : b;
    w::write_u16(p, b * w::kBlockSize + 2, static_cast<std::uint16_t>(35900 + 20 * firing) % 36000);
    for (std::size_t s = 0; s < 2; ++s)
      for (std::size_t l = 0; l < w::kLasers; ++l) {
        const auto at = w::channel_offset(b, s, l);
        w::write_u16(p, at, static_cast<std::uint16_t>(2000 + 37 * l + 500 * (b % 2)));  // dual: echoes differ
        p[at + 2] = static_cast<std::uint8_t>(l);
      }
  }
  w::write_u32(p, w::kTimestampOffset, 123456789);
  p[w::kReturnModeOffset] = mode;
  p[w::kProductOffset] = w::kProductVlp16;
  return p;
}

void report(benchmark::State& state, std::size_t returns) {
  state.SetItemsProcessed(state.iterations());
  state.counters["x_sensor"] = benchmark::Counter(static_cast<double>(state.iterations()) / kSensorPacketsPerSecond,
                                                  benchmark::Counter::kIsRate);
  state.counters["returns/pkt"] = static_cast<double>(returns) / static_cast<double>(state.iterations());
}

void decode_loop(benchmark::State& state, const std::vector<Packet>& packets) {
  if (packets.empty()) {
    state.SkipWithError("no packets");
    return;
  }
  fsd::PacketDecoder decoder(fsd::LaserTable::builtin(), 0.5, 130.0);
  std::vector<fsd::Vlp16Return> out;
  out.reserve(768);
  std::size_t i = 0, returns = 0;
  for (auto _ : state) {
    out.clear();
    decoder.decode(packets[i], out);
    returns += out.size();
    benchmark::DoNotOptimize(out.data());
    if (++i == packets.size()) i = 0;
  }
  report(state, returns);
}

void BM_DecodeRecorded(benchmark::State& state) {
  static const auto packets = recorded_packets();
  decode_loop(state, packets);
}
BENCHMARK(BM_DecodeRecorded);

void BM_DecodeFullStrongest(benchmark::State& state) {
  decode_loop(state, {full_packet(fsd::wire::vlp16::kReturnStrongest)});
}
BENCHMARK(BM_DecodeFullStrongest);

void BM_DecodeFullDual(benchmark::State& state) { decode_loop(state, {full_packet(fsd::wire::vlp16::kReturnDual)}); }
BENCHMARK(BM_DecodeFullDual);

// Decoder + sensor clock + frame assembly into Scans: the whole driver path per packet.
void BM_ScanBuilderRecorded(benchmark::State& state) {
  static const auto packets = recorded_packets();
  if (packets.empty()) {
    state.SkipWithError("no packets");
    return;
  }
  std::size_t points = 0;
  fsd::Vlp16ScanBuilder builder(fsd::Vlp16Config{}, [&](fsd::Scan&& s) { points += s.points.size(); });
  std::size_t i = 0;
  double t = 0;
  for (auto _ : state) {
    builder.on_data_packet(t, packets[i]);
    t += 1.327104e-3;
    if (++i == packets.size()) i = 0;
  }
  builder.flush();
  benchmark::DoNotOptimize(points);
  report(state, builder.decode_counters().returns);
}
BENCHMARK(BM_ScanBuilderRecorded);

}  // namespace

BENCHMARK_MAIN();
