// The first full revolution of a capture (fsd detect on a pcap), on the shared real VLP-16 capture: about one
// turn of packets, whose frames cut at 0° are both partial; taken from the first return's azimuth it is one whole
// sweep of every laser.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <string>

#include "tests/scratch_dir.hpp"

#include "drivers/sim/sensors/pcap_writer.hpp"
#include "drivers/vlp16/pcap_dump.hpp"
#include "drivers/vlp16/pcap_reader.hpp"
#include "drivers/vlp16/pcap_revolution.hpp"

namespace fsd {
namespace {

const char* kCapture = "../shared/data/vlp16/velodyne_vlp16.pcap";

TEST(Vlp16Revolution, TheSharedCaptureGivesOneWholeTurn) {
  const auto all = dump_vlp16_pcap(kCapture, Vlp16Config{}, [](const Vlp16Return&) {});
  const Vlp16Revolution rev = read_first_revolution(kCapture, Vlp16Config{});
  EXPECT_TRUE(rev.complete);
  EXPECT_EQ(rev.azimuth_span_deg, 360.0);
  EXPECT_GT(rev.packets, 0u);
  EXPECT_LT(rev.packets, all.decode.packets);  // reading stops once the turn is whole
  // Less than the capture's returns (it holds ~400° of azimuth), and every degree of azimuth has points.
  EXPECT_LT(rev.scan.points.size(), all.decode.returns);
  EXPECT_GT(rev.scan.points.size(), all.decode.returns * 300 / 400);
  std::array<int, 360> per_degree{};
  for (const auto& p : rev.scan.points) {
    const auto d = static_cast<std::size_t>(std::fmod(rad2deg(p.azimuth) + 360.0, 360.0));
    ++per_degree[std::min<std::size_t>(d, 359)];
  }
  for (std::size_t d = 0; d < per_degree.size(); ++d) EXPECT_GT(per_degree[d], 0) << d << "°";
}

TEST(Vlp16Revolution, AShortCaptureGivesWhatItHas) {
  // The capture's first 40 data packets (40 × 12 × 0.4° ≈ 190° of azimuth) rewritten: no whole turn, the partial
  // sweep instead.
  const std::string path = test::scratch_path("short.pcap");
  {
    sim::PcapWriter w(path);
    PcapReader r(kCapture, {wire::vlp16::kDataPort});
    UdpDatagram d;
    for (int i = 0; i < 40 && r.next(d); ++i) w.write(d.capture_time, d.payload);
  }
  const Vlp16Revolution rev = read_first_revolution(path, Vlp16Config{});
  EXPECT_FALSE(rev.complete);
  EXPECT_EQ(rev.packets, 40u);
  EXPECT_GT(rev.azimuth_span_deg, 170.0);
  EXPECT_LT(rev.azimuth_span_deg, 210.0);
  EXPECT_GT(rev.scan.points.size(), 5000u);
}

TEST(Vlp16Revolution, TellsAPcapFromText) {
  EXPECT_TRUE(looks_like_pcap(kCapture));
  EXPECT_FALSE(looks_like_pcap("../shared/tracks/epfl_track_1.csv"));
  EXPECT_FALSE(looks_like_pcap("/nonexistent.pcap"));
}

}  // namespace
}  // namespace fsd
