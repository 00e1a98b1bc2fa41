// The pcap writer: records read back with libpcap carry the payload behind Ethernet/IPv4/UDP headers of a real
// VLP-16, and tcpdump (when installed) reads the file.
#include <gtest/gtest.h>
#include <pcap/pcap.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "drivers/sim/sensors/lidar_model.hpp"
#include "drivers/sim/sensors/pcap_writer.hpp"
#include "tests/scratch_dir.hpp"
#include "tests/sim/world_test_util.hpp"

namespace fsd::sim {
namespace {

struct Record {
  double t;
  std::vector<std::uint8_t> frame;
};

std::vector<Record> read_all(const std::filesystem::path& path, int* link_type = nullptr) {
  char err[PCAP_ERRBUF_SIZE];
  pcap_t* p = pcap_open_offline(path.c_str(), err);
  EXPECT_NE(p, nullptr) << err;
  if (!p) return {};
  if (link_type) *link_type = pcap_datalink(p);
  std::vector<Record> out;
  pcap_pkthdr* hdr = nullptr;
  const u_char* data = nullptr;
  while (pcap_next_ex(p, &hdr, &data) == 1) {
    EXPECT_EQ(hdr->caplen, hdr->len);
    out.push_back({static_cast<double>(hdr->ts.tv_sec) + hdr->ts.tv_usec * 1e-6,
                   std::vector<std::uint8_t>(data, data + hdr->caplen)});
  }
  pcap_close(p);
  return out;
}

unsigned be16(const std::vector<std::uint8_t>& b, std::size_t at) { return b[at] << 8 | b[at + 1]; }

TEST(LidarPcap, RecordsCarryThePayloadBehindRealSensorHeaders) {
  const std::filesystem::path path = fsd::test::scratch_path("writer.pcap");
  std::vector<std::vector<std::uint8_t>> payloads;
  for (int i = 0; i < 5; ++i) {
    std::vector<std::uint8_t> p(i == 4 ? 512 : 1206);
    for (std::size_t k = 0; k < p.size(); ++k) p[k] = static_cast<std::uint8_t>(k * 7 + static_cast<std::size_t>(i));
    payloads.push_back(p);
  }
  {
    PcapWriter w(path.string());
    for (int i = 0; i < 4; ++i) w.write(100.25 + i * 0.001327, payloads[static_cast<std::size_t>(i)]);
    w.write(100.5, payloads[4], 8308);
    EXPECT_EQ(w.records(), 5u);
  }
  int link = -1;
  const auto recs = read_all(path, &link);
  EXPECT_EQ(link, DLT_EN10MB);
  ASSERT_EQ(recs.size(), 5u);
  for (std::size_t i = 0; i < recs.size(); ++i) {
    const auto& f = recs[i].frame;
    const auto& payload = payloads[i];
    ASSERT_EQ(f.size(), 14 + 20 + 8 + payload.size());
    EXPECT_EQ(be16(f, 12), 0x0800u);                  // IPv4
    EXPECT_EQ(f[14], 0x45);                           // version 4, 20-byte header
    EXPECT_EQ(be16(f, 16), 20 + 8 + payload.size());  // total length
    EXPECT_EQ(f[23], 17);                             // UDP
    EXPECT_EQ(std::vector<int>(f.begin() + 26, f.begin() + 30), (std::vector<int>{192, 168, 1, 201}));
    // The header checksum sums to 0xFFFF over the header, checksum included.
    unsigned sum = 0;
    for (std::size_t k = 14; k < 34; k += 2) sum += be16(f, k);
    while (sum >> 16) sum = (sum & 0xFFFF) + (sum >> 16);
    EXPECT_EQ(sum, 0xFFFFu);
    const unsigned port = i == 4 ? 8308u : 2368u;
    EXPECT_EQ(be16(f, 34), port);
    EXPECT_EQ(be16(f, 36), port);
    EXPECT_EQ(be16(f, 38), 8 + payload.size());
    EXPECT_TRUE(std::equal(payload.begin(), payload.end(), f.begin() + 42));
  }
  EXPECT_NEAR(recs[0].t, 100.25, 1e-6);
  EXPECT_NEAR(recs[3].t, 100.25 + 3 * 0.001327, 1e-6);
  std::filesystem::remove(path);
}

TEST(LidarPcap, RejectsWhatDoesNotFit) {
  EXPECT_THROW(PcapWriter("/nonexistent-dir/x.pcap"), std::runtime_error);
  const std::filesystem::path path = fsd::test::scratch_path("reject.pcap");
  PcapWriter w(path.string());
  std::vector<std::uint8_t> huge(PcapWriter::kMaxPayload + 1);
  EXPECT_THROW(w.write(1.0, huge), std::invalid_argument);
  std::vector<std::uint8_t> ok(10);
  EXPECT_THROW(w.write(-1.0, ok), std::invalid_argument);
  EXPECT_EQ(w.records(), 0u);
  std::filesystem::remove(path);
}

TEST(LidarPcap, SimulatedScanWrittenAndReadByTcpdump) {
  const std::filesystem::path path = fsd::test::scratch_path("scan.pcap");
  const World world(test::make_track({test::make_cone(6.0, 0.5)}), test::bare_config(), 1);
  std::vector<std::vector<std::uint8_t>> sent;
  {
    PcapWriter w(path.string());
    LidarModel lidar(LidarConfig{}, world, 1);
    lidar.advance_to(
        0.1, [](Stamp) { return Pose3::Identity(); },
        [&](Stamp t, std::span<const std::uint8_t> b) {
          w.write(t, b);
          sent.emplace_back(b.begin(), b.end());
        });
  }
  const auto recs = read_all(path);
  ASSERT_EQ(recs.size(), sent.size());
  for (std::size_t i = 0; i < sent.size(); ++i)
    EXPECT_TRUE(std::equal(sent[i].begin(), sent[i].end(), recs[i].frame.begin() + 42)) << i;

  if (std::system("command -v tcpdump > /dev/null 2>&1") != 0) GTEST_SKIP() << "tcpdump not installed";
  const std::string cmd = "tcpdump -nn -r '" + path.string() + "' 2>/dev/null";
  FILE* out = popen(cmd.c_str(), "r");
  ASSERT_NE(out, nullptr);
  char line[512];
  std::size_t lines = 0, udp_lines = 0;
  while (fgets(line, sizeof line, out)) {
    ++lines;
    udp_lines +=
        std::string(line).find("192.168.1.201.2368 > 255.255.255.255.2368: UDP, length 1206") != std::string::npos;
  }
  EXPECT_EQ(pclose(out), 0);
  EXPECT_EQ(lines, sent.size());
  EXPECT_EQ(udp_lines, sent.size());
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace fsd::sim
