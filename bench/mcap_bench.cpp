// MCAP recording cost at full sensor rate (goal: the recorder ≤ 5 % of one core). One "second" of a run is the
// daemon's raw input plus a derived JSON channel: 754 VLP-16 packets of 1206 bytes (the shared capture's real
// packets, cycled), 50 NMEA epochs (~3 sentences each), 15 JPEG frames of 30 KB (random bytes: JPEG data does
// not compress further) and 50 JSON vehicle states. Run from the worktree root:
//   build/bench/mcap_bench
// "x_realtime" = recorded seconds per CPU second (100 / x_realtime = percent of one core); bytes_per_second =
// recorded payload per CPU second (rates use CPU time, so a loaded machine does not inflate them). CRC-32: the slicing-by-8 table against the plain byte-at-a-time loop, in the same run.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "common/mcap/crc32.hpp"
#include "common/mcap/linear_reader.hpp"
#include "common/mcap/summary_reader.hpp"
#include "common/mcap/writer.hpp"
#include "drivers/vlp16/pcap_reader.hpp"

namespace {

using namespace fsd::mcap;

struct Frame {
  int channel;  // index into the channel list below
  Timestamp t;
  Bytes data;
};

std::vector<Bytes> vlp16_packets() {
  std::vector<Bytes> out;
  try {
    fsd::PcapReader reader("../shared/data/vlp16/velodyne_vlp16.pcap", {2368});
    fsd::UdpDatagram d;
    while (reader.next(d)) out.emplace_back(d.payload.begin(), d.payload.end());
  } catch (const fsd::PcapError& e) {
    std::fprintf(stderr, "%s (run from the worktree root)\n", e.what());
  }
  if (out.empty()) out.emplace_back(1206, 0);
  return out;
}

// One second of a run, in time order.
const std::vector<Frame>& one_second() {
  static const std::vector<Frame> frames = [] {
    std::vector<Frame> f;
    const auto packets = vlp16_packets();
    std::mt19937 rng(7);
    // The capture holds 84 packets: cycled as they are, zstd would find each one again and compress them far
    // better than a moving car's sweeps. Each repeat gets range noise of +-4 mm on every return and a new
    // timestamp, so only what really repeats in a VLP-16 packet (flags, azimuth steps, layout) stays.
    for (int i = 0; i < 754; ++i) {
      Bytes p = packets[static_cast<std::size_t>(i) % packets.size()];
      if (p.size() == 1206) {
        for (std::size_t b = 0; b < 12; ++b)
          for (std::size_t k = 0; k < 32; ++k) {
            const std::size_t at = b * 100 + 4 + k * 3;
            const int d = p[at] | p[at + 1] << 8;
            if (d == 0) continue;
            const int noisy = std::clamp(d + static_cast<int>(rng() % 5) - 2, 1, 65535);
            p[at] = static_cast<std::uint8_t>(noisy);
            p[at + 1] = static_cast<std::uint8_t>(noisy >> 8);
          }
        const std::uint32_t us = static_cast<std::uint32_t>(i) * 1326;
        for (int k = 0; k < 4; ++k) p[1200 + k] = static_cast<std::uint8_t>(us >> (8 * k));
      }
      f.push_back({0, static_cast<Timestamp>(i) * 1'000'000'000 / 754, std::move(p)});
    }
    for (int i = 0; i < 50; ++i) {
      char s[400];
      const int n =
          std::snprintf(s, sizeof s,
                        "$GPGGA,1234%02d.%02d,4724.%05d,N,00832.%05d,E,4,12,0.8,441.2,M,47.3,M,1.0,0000*5B\r\n"
                        "$GPRMC,1234%02d.%02d,A,4724.%05d,N,00832.%05d,E,%05.2f,087.3,100517,,,D*6A\r\n"
                        "$PASHR,1234%02d.%02d,087.31,T,-0.52,1.21,,0.012,0.012,0.080,2,1*1F\r\n",
                        i / 50, i * 2, 10000 + i * 17, 20000 + i * 13, i / 50, i * 2, 10000 + i * 17, 20000 + i * 13,
                        14.2 + i * 0.01, i / 50, i * 2);
      f.push_back({1, static_cast<Timestamp>(i) * 20'000'000, Bytes(s, s + n)});
    }
    for (int i = 0; i < 15; ++i) {
      Bytes jpeg(30 * 1024);
      for (auto& b : jpeg) b = static_cast<std::uint8_t>(rng());
      f.push_back({2, static_cast<Timestamp>(i) * 1'000'000'000 / 15, std::move(jpeg)});
    }
    for (int i = 0; i < 50; ++i) {
      char s[400];
      const int n =
          std::snprintf(s, sizeof s,
                        R"({"t":%.3f,"x":%.4f,"y":%.4f,"yaw":%.5f,"vx":%.3f,"vy":%.3f,"yaw_rate":%.4f,)"
                        R"("ax":%.3f,"ay":%.3f,"steering":%.4f,"as_state":"Driving","lap":1})",
                        i * 0.02, 12.3 + i * 0.28, -4.1 + i * 0.05, 0.3 + i * 0.001, 14.1, 0.12, 0.21, 0.4, 3.1, 0.05);
      f.push_back({3, static_cast<Timestamp>(i) * 20'000'000, Bytes(s, s + n)});
    }
    std::stable_sort(f.begin(), f.end(), [](const Frame& a, const Frame& b) { return a.t < b.t; });
    return f;
  }();
  return frames;
}

std::size_t payload_per_second() {
  std::size_t n = 0;
  for (const auto& f : one_second()) n += f.data.size();
  return n;
}

// Writes `seconds` of the run; returns the file.
Bytes record(int seconds, Compression c, benchmark::State* state = nullptr) {
  BufferSink sink;
  sink.data.reserve(static_cast<std::size_t>(seconds) * payload_per_second() + (1 << 20));
  WriterOptions o;
  o.compression = c;
  Writer w(sink, o);
  const std::uint16_t ch[] = {
      w.add_channel("/raw/vlp16/data", "fsd.raw", w.add_schema("fsd.raw.vlp16_data", "fsd.raw", {})),
      w.add_channel("/raw/gnss", "fsd.raw", w.add_schema("fsd.raw.nmea", "fsd.raw", {})),
      w.add_channel("/raw/camera", "fsd.raw", w.add_schema("fsd.raw.jpeg", "fsd.raw", {})),
      w.add_channel("/state", "json", 0)};
  for (int s = 0; s < seconds; ++s)
    for (const auto& f : one_second()) {
      const Timestamp t = static_cast<Timestamp>(s) * 1'000'000'000 + f.t;
      w.write_message(ch[f.channel], t, t, f.data);
    }
  w.close();
  if (state) state->counters["file_MB_per_recorded_s"] = static_cast<double>(sink.data.size()) / seconds / 1e6;
  return std::move(sink.data);
}

void report(benchmark::State& state, int seconds) {
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations()) * seconds *
                          static_cast<std::int64_t>(payload_per_second()));
  // Recorded seconds per CPU second: 100 / x_realtime is the share of one core in percent.
  state.counters["x_realtime"] = benchmark::Counter(
      static_cast<double>(seconds) * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

constexpr int kSeconds = 5;

void BM_McapWrite(benchmark::State& state) {
  const auto c = static_cast<Compression>(state.range(0));
  for (auto _ : state) benchmark::DoNotOptimize(record(kSeconds, c, &state));
  report(state, kSeconds);
}
BENCHMARK(BM_McapWrite)
    ->Arg(static_cast<int>(Compression::Zstd))
    ->Arg(static_cast<int>(Compression::None))
    ->ArgName("zstd1_none0")
    ->Unit(benchmark::kMillisecond);

void BM_McapReadLinear(benchmark::State& state) {
  const auto file = record(kSeconds, static_cast<Compression>(state.range(0)));
  for (auto _ : state) {
    LinearReader r(file);
    std::size_t n = 0;
    while (auto rec = r.next()) n += std::holds_alternative<Message>(rec->record);
    benchmark::DoNotOptimize(n);
  }
  report(state, kSeconds);
}
BENCHMARK(BM_McapReadLinear)
    ->Arg(static_cast<int>(Compression::Zstd))
    ->Arg(static_cast<int>(Compression::None))
    ->ArgName("zstd1_none0")
    ->Unit(benchmark::kMillisecond);

void BM_McapReadIndexed(benchmark::State& state) {
  const auto file = record(kSeconds, Compression::Zstd);
  for (auto _ : state) {
    SummaryReader r(file);
    std::size_t n = 0;
    r.for_each_message([&](const Message& m, const fsd::mcap::Channel&) { n += m.data.size(); });
    benchmark::DoNotOptimize(n);
  }
  report(state, kSeconds);
}
BENCHMARK(BM_McapReadIndexed)->Unit(benchmark::kMillisecond);

// The naive peer of crc32_update: one table lookup per byte.
std::uint32_t crc32_bytewise(std::span<const std::uint8_t> b) {
  static const auto table = [] {
    std::array<std::uint32_t, 256> t{};
    for (std::uint32_t i = 0; i < 256; ++i) {
      std::uint32_t c = i;
      for (int k = 0; k < 8; ++k) c = (c & 1u) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
      t[i] = c;
    }
    return t;
  }();
  std::uint32_t c = ~0u;
  for (auto x : b) c = table[(c ^ x) & 0xFF] ^ (c >> 8);
  return ~c;
}

void BM_Crc32(benchmark::State& state) {
  Bytes data(1 << 20);
  for (std::size_t i = 0; i < data.size(); ++i) data[i] = static_cast<std::uint8_t>(i * 2654435761u >> 13);
  const bool naive = state.range(0) == 1;
  if (crc32(data) != crc32_bytewise(data)) state.SkipWithError("slicing-by-8 and bytewise CRCs differ");
  for (auto _ : state) benchmark::DoNotOptimize(naive ? crc32_bytewise(data) : crc32(data));
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations()) * static_cast<std::int64_t>(data.size()));
}
BENCHMARK(BM_Crc32)->Arg(0)->Arg(1)->ArgName("bytewise");

}  // namespace

BENCHMARK_MAIN();
