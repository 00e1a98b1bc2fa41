// The recorded VLP-16 capture ../shared/data/vlp16/velodyne_vlp16.pcap (84 data packets, product byte 0x21 of
// early firmware, strongest return; 16 position packets without GPS) through the pcap reader and the decoder,
// checked against the packet bytes, against hand computation and against the geometry of the ground.
#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "drivers/vlp16/pcap_dump.hpp"
#include "drivers/vlp16/pcap_reader.hpp"
#include "drivers/vlp16/position_packet.hpp"
#include "tests/scratch_dir.hpp"

namespace fsd {
namespace {

const char* kPcap = "../shared/data/vlp16/velodyne_vlp16.pcap";

std::vector<std::uint8_t> read_file(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
}

std::vector<Vlp16Return> all_returns(PcapDumpSummary* summary = nullptr) {
  std::vector<Vlp16Return> out;
  const auto s = dump_vlp16_pcap(kPcap, Vlp16Config{}, [&](const Vlp16Return& r) { out.push_back(r); });
  if (summary) *summary = s;
  return out;
}

// The return of `laser` fired `t_us` (sensor time) in the capture.
const Vlp16Return& find_return(const std::vector<Vlp16Return>& all, int laser, double t_us) {
  const auto it = std::find_if(
      all.begin(), all.end(), [&](const Vlp16Return& r) { return r.laser == laser && std::abs(r.t_us - t_us) < 1e-6; });
  if (it == all.end()) throw std::runtime_error("return not found: laser " + std::to_string(laser));
  return *it;
}

// Counts the non-zero distance words of the data packets by walking the file's bytes directly: classic pcap,
// Ethernet + 20-byte IPv4 + UDP headers (42 bytes) before each payload.
std::size_t nonzero_distances_in_file() {
  const auto f = read_file(kPcap);
  std::size_t at = 24, count = 0;
  while (at + 16 <= f.size()) {
    const std::size_t caplen = f[at + 8] | (f[at + 9] << 8) | (f[at + 10] << 16) | (std::size_t{f[at + 11]} << 24);
    const std::size_t frame = at + 16;
    const unsigned port = (f[frame + 36] << 8) | f[frame + 37];
    if (port == 2368 && caplen == 42 + 1206)
      for (std::size_t b = 0; b < 12; ++b)
        for (std::size_t c = 0; c < 32; ++c) {
          const std::size_t w = frame + 42 + b * 100 + 4 + c * 3;
          if (f[w] != 0 || f[w + 1] != 0) ++count;
        }
    at = frame + caplen;
  }
  return count;
}

TEST(Vlp16Pcap, CountsOfTheRecording) {
  PcapDumpSummary s;
  const auto returns = all_returns(&s);
  // Every non-zero distance of the file is a valid return: the shortest is 2.43 m and the longest 109.85 m,
  // inside the default 0.5 .. 130 m. 84 packets × 384 channels = 32256, of which 12677 have no echo (sky).
  const auto expected = nonzero_distances_in_file();
  EXPECT_EQ(expected, 19579u);
  EXPECT_EQ(returns.size(), expected);
  EXPECT_EQ(s.decode.packets, 84u);
  EXPECT_EQ(s.decode.rejected(), 0u);
  EXPECT_EQ(s.decode.no_return, 32256u - expected);
  EXPECT_EQ(s.decode.out_of_range, 0u);
  EXPECT_EQ(s.lost_packets, 0u);
  // The capture spans 250.35° → 360° → 290.80°: one cut at 0° and the partial rest.
  EXPECT_EQ(s.frames, 2u);
  // Position packets: timestamp only, no GPS and no PPS connected; their IPv4 headers claim 1234 bytes.
  EXPECT_EQ(s.position.packets, 16u);
  EXPECT_EQ(s.position.nmea_absent, 16u);
  EXPECT_EQ(s.last_pps, PpsState::Absent);
  EXPECT_EQ(s.pcap.records, 100u);
  EXPECT_EQ(s.pcap.bad_ip_length, 16u);
  const auto [lo, hi] = std::minmax_element(returns.begin(), returns.end(),
                                            [](const auto& a, const auto& b) { return a.distance_m < b.distance_m; });
  EXPECT_DOUBLE_EQ(lo->distance_m, 2.430);
  EXPECT_DOUBLE_EQ(hi->distance_m, 109.848);
}

TEST(Vlp16Pcap, ReturnsComputedByHandFromThePacketBytes) {
  const auto all = all_returns();
  // Elevation ω and vertical offset from the manual's table; x = d cosω cosα, y = -d cosω sinα, z = d sinω + off.

  // (1) First data packet. Bytes 1200..1205: 2d e9 d7 13 37 21 → timestamp 0x13d7e92d = 332917037 µs,
  //     strongest return, product 0x21. Block 0 starts ff ee cb 61 → azimuth 0x61cb = 25035 → 250.35°.
  //     Laser 0, sequence 0 (first channel): 84 06 2c → 0x0684 = 1668 × 2 mm = 3.336 m, reflectivity 44.
  //     ω = -15°: x = 3.336 cos15° cos250.35° = -1.083584, y = -3.336 cos15° sin250.35° = 3.034674,
  //     z = 3.336 sin(-15°) + 0.0112 = -0.852220. Time: the packet's first firing, 332917037.000 µs.
  {
    const auto& r = find_return(all, 0, 332917037.0);
    EXPECT_NEAR(r.azimuth_deg, 250.35, 1e-9);
    EXPECT_DOUBLE_EQ(r.distance_m, 3.336);
    EXPECT_EQ(r.intensity, 44);
    EXPECT_NEAR(r.x, -1.083583838, 1e-6);
    EXPECT_NEAR(r.y, 3.034674182, 1e-6);
    EXPECT_NEAR(r.z, -0.852220334, 1e-6);
  }
  // (2) Same packet, block 3: ff ee 42 62 → 0x6242 = 25154 → 251.54°; block 4 is at 251.94° (step 0.40°).
  //     Sequence 1, laser 4 (-11°, +8.1 mm): 6b 06 60 → 0x066b = 1643 → 3.286 m, reflectivity 96.
  //     Fires at 3 × 110.592 + 55.296 + 4 × 2.304 = 396.288 µs → t = 332917433.288 µs.
  //     Azimuth 251.54° + 0.40° × (55.296 + 9.216) / 110.592 = 251.54° + 0.40° × 0.583333 = 251.773333°.
  //     x = -1.008902, y = 3.063786, z = 3.286 sin(-11°) + 0.0081 = -0.618898.
  {
    const auto& r = find_return(all, 4, 332917433.288);
    EXPECT_NEAR(r.azimuth_deg, 251.7733333333, 1e-9);
    EXPECT_DOUBLE_EQ(r.distance_m, 3.286);
    EXPECT_EQ(r.intensity, 96);
    EXPECT_NEAR(r.firing_offset_us, 396.288, 1e-9);
    EXPECT_NEAR(r.x, -1.008901983, 1e-6);
    EXPECT_NEAR(r.y, 3.063786195, 1e-6);
    EXPECT_NEAR(r.z, -0.618898359, 1e-6);
  }
  // (3) The packet with timestamp bytes 39 5b d8 13 → 332946233 µs, the last before the 360° wrap.
  //     Block 10: ff ee 60 8c → 35936 (359.36°); block 11 (last): ff ee 89 8c → 35977 (359.77°). The last block
  //     has no successor, so it reuses the previous step: 0.41°.
  //     Block 11, sequence 1, laser 8 (-7°, +5.1 mm): 73 30 10 → 0x3073 = 12403 → 24.806 m, reflectivity 16.
  //     Fires at 11 × 110.592 + 55.296 + 8 × 2.304 = 1290.240 µs → t = 332947523.240 µs.
  //     Azimuth 359.77° + 0.41° × 73.728 / 110.592 = 359.77° + 0.273333° = 360.043333° → wraps to 0.043333°.
  //     x = 24.806 cos7° cos0.043333° = 24.621093, y = -0.018621 (just right of +x), z = -3.017991.
  {
    const auto& r = find_return(all, 8, 332947523.240);
    EXPECT_NEAR(r.azimuth_deg, 0.0433333333, 1e-9);
    EXPECT_DOUBLE_EQ(r.distance_m, 24.806);
    EXPECT_EQ(r.intensity, 16);
    EXPECT_NEAR(r.x, 24.621092796, 1e-6);
    EXPECT_NEAR(r.y, -0.018621166, 1e-6);
    EXPECT_NEAR(r.z, -3.017990933, 1e-6);
    EXPECT_EQ(r.ring, 4);
    std::string row;
    append_csv_row(row, r);
    EXPECT_EQ(row, "332947523.240,8,0.0433,24.806,16,24.6211,-0.0186,-3.0180\n");
  }
  // (4) Same block, sequence 0, laser 15 (+15°, -11.2 mm): 64 11 0f → 0x1164 = 4452 → 8.904 m, reflectivity 15.
  //     Fires at 1216.512 + 15 × 2.304 = 1251.072 µs → t = 332947484.072 µs.
  //     Azimuth 359.77° + 0.41° × 34.56 / 110.592 = 359.898125° (still before the wrap).
  //     x = 8.600590, y = 0.015292 (left of +x), z = 8.904 sin15° - 0.0112 = 2.293325.
  {
    const auto& r = find_return(all, 15, 332947484.072);
    EXPECT_NEAR(r.azimuth_deg, 359.898125, 1e-9);
    EXPECT_DOUBLE_EQ(r.distance_m, 8.904);
    EXPECT_EQ(r.intensity, 15);
    EXPECT_NEAR(r.x, 8.600589962, 1e-6);
    EXPECT_NEAR(r.y, 0.015292331, 1e-6);
    EXPECT_NEAR(r.z, 2.293324778, 1e-6);
    EXPECT_EQ(r.ring, 15);
  }
}

// Least-squares plane z = a x + b y + c through the points; returns (a, b, c) and the RMS residual.
struct Plane {
  Eigen::Vector3d abc;
  double rms;
  double height() const { return -abc.z() / std::sqrt(1 + abc.x() * abc.x() + abc.y() * abc.y()); }
  double tilt_deg() const { return std::atan(std::hypot(abc.x(), abc.y())) * 180 / std::numbers::pi; }
};
Plane fit_plane(const std::vector<Eigen::Vector3d>& pts) {
  Eigen::MatrixXd A(pts.size(), 3);
  Eigen::VectorXd z(pts.size());
  for (std::size_t i = 0; i < pts.size(); ++i) {
    A.row(static_cast<Eigen::Index>(i)) << pts[i].x(), pts[i].y(), 1.0;
    z(static_cast<Eigen::Index>(i)) = pts[i].z();
  }
  Plane p;
  p.abc = A.colPivHouseholderQr().solve(z);
  p.rms = std::sqrt((A * p.abc - z).squaredNorm() / static_cast<double>(pts.size()));
  return p;
}

TEST(Vlp16Pcap, GroundRingsLieOnOneGroundPlane) {
  const auto all = all_returns();
  // Azimuth 0°..210° sees open ground all around (210°..330° looks at something 3.3 m away). In that sector the
  // three lowest rings must each lie on a plane about a sensor height below the origin, the same plane for all
  // three, nearly level (the sensor sits ~1.8 m up, pitched by ~3°), at the horizontal range the beam's
  // elevation predicts: h / tan(-ω).
  std::vector<Plane> planes;
  std::vector<double> median_range;
  for (const int laser : {0, 2, 4}) {  // rings 0, 1, 2: -15°, -13°, -11°
    std::vector<Eigen::Vector3d> pts;
    std::vector<double> range;
    for (const auto& r : all)
      if (r.laser == laser && r.azimuth_deg < 210.0) {
        pts.emplace_back(r.x, r.y, r.z);
        range.push_back(std::hypot(r.x, r.y));
      }
    ASSERT_GT(pts.size(), 1000u) << "laser " << laser;
    planes.push_back(fit_plane(pts));
    std::nth_element(range.begin(), range.begin() + static_cast<long>(range.size() / 2), range.end());
    median_range.push_back(range[range.size() / 2]);
    const auto& p = planes.back();
    EXPECT_LT(p.rms, 0.04) << "laser " << laser;
    EXPECT_GT(p.height(), 1.70) << "laser " << laser;
    EXPECT_LT(p.height(), 1.90) << "laser " << laser;
    EXPECT_LT(p.tilt_deg(), 5.0) << "laser " << laser;
  }
  EXPECT_NEAR(planes[0].height(), planes[1].height(), 0.05);
  const double h = planes[0].height();
  EXPECT_NEAR(median_range[0], h / std::tan(15 * std::numbers::pi / 180),
              0.15 * h / std::tan(15 * std::numbers::pi / 180));
  EXPECT_NEAR(median_range[1], h / std::tan(13 * std::numbers::pi / 180),
              0.15 * h / std::tan(13 * std::numbers::pi / 180));
  EXPECT_LT(median_range[0], median_range[1]);
  EXPECT_LT(median_range[1], median_range[2]);
}

TEST(Vlp16Pcap, CsvHasTheHeaderAndOneRowPerReturn) {
  std::string csv(kLidarDumpCsvHeader);
  csv += '\n';
  dump_vlp16_pcap(kPcap, Vlp16Config{}, [&](const Vlp16Return& r) { append_csv_row(csv, r); });
  std::istringstream in(csv);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "t_us,laser,azimuth_deg,distance_m,intensity,x,y,z");
  std::size_t rows = 0;
  while (std::getline(in, line)) {
    ++rows;
    ASSERT_EQ(std::count(line.begin(), line.end(), ','), 7) << line;
  }
  EXPECT_EQ(rows, 19579u);
  EXPECT_NE(csv.find("332917037.000,0,250.3500,3.336,44,-1.0836,3.0347,-0.8522\n"), std::string::npos);
}

TEST(Vlp16Pcap, ReaderDeliversPayloadsWithCaptureTimes) {
  PcapReader reader(kPcap, {2368});
  UdpDatagram d;
  ASSERT_TRUE(reader.next(d));
  // First record header: ts 1415644617 s + 383637 µs; the payload's first bytes are the block flag.
  EXPECT_NEAR(d.capture_time, 1415644617.383637, 1e-6);
  EXPECT_EQ(d.src_port, 2368);
  EXPECT_EQ(d.dst_port, 2368);
  ASSERT_EQ(d.payload.size(), 1206u);
  EXPECT_EQ(d.payload[0], 0xFF);
  EXPECT_EQ(d.payload[1], 0xEE);
  std::size_t n = 1;
  while (reader.next(d)) ++n;
  EXPECT_EQ(n, 84u);
  EXPECT_EQ(reader.counters().filtered, 16u);  // the position packets on 8308
}

TEST(Vlp16Pcap, LinuxCookedAndRawIpCapturesGiveTheSamePayloads) {
  // The fuzz seeds hold the recording's first data packet and first position packet behind three link layers:
  // Ethernet (as recorded), Linux cooked capture v1 (16-byte header) and raw IPv4.
  const auto payloads = [](const std::string& file) {
    PcapReader reader("tests/fuzz/corpus/vlp16_pcap/" + file);
    std::vector<std::vector<std::uint8_t>> out;
    UdpDatagram d;
    while (reader.next(d)) out.emplace_back(d.payload.begin(), d.payload.end());
    EXPECT_EQ(reader.counters().malformed, 0u) << file;
    return out;
  };
  const auto ethernet = payloads("ethernet.pcap");
  ASSERT_EQ(ethernet.size(), 2u);
  EXPECT_EQ(ethernet[0].size(), 1206u);
  EXPECT_EQ(ethernet[1].size(), 512u);
  EXPECT_EQ(payloads("linux_sll.pcap"), ethernet);
  EXPECT_EQ(payloads("raw_ip.pcap"), ethernet);
}

TEST(Vlp16Pcap, PositionPacketOfTheRecording) {
  PcapReader reader(kPcap, {8308});
  UdpDatagram d;
  ASSERT_TRUE(reader.next(d));
  PositionPacket p;
  ASSERT_EQ(parse_position_packet(d.payload, p), PositionStatus::Ok);
  // Bytes 198..201: 61 f9 d7 13 → 0x13d7f961 = 332921185 µs; PPS byte 0; NMEA field all NUL.
  EXPECT_EQ(p.timestamp_us, 332921185u);
  EXPECT_EQ(p.pps, PpsState::Absent);
  EXPECT_EQ(p.nmea_state, NmeaState::Absent);
}

TEST(Vlp16Pcap, MissingCorruptAndTruncatedFilesAreClearErrors) {
  const auto expect_error = [](const std::string& path, const std::string& fragment) {
    try {
      dump_vlp16_pcap(path, Vlp16Config{}, [](const Vlp16Return&) {});
      ADD_FAILURE() << "no error for " << path;
    } catch (const PcapError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(path), std::string::npos) << what;
      EXPECT_NE(what.find(fragment), std::string::npos) << what;
    }
  };
  expect_error(test::scratch_path("no_such_capture.pcap"), "no such file");
  expect_error("../shared/data/vlp16/vlp16_lasers.csv", "unknown file format");

  // Cut in the middle of the 4th record: the first three packets' returns arrive, then the error.
  const auto bytes = read_file(kPcap);
  const std::string truncated = test::scratch_path("truncated.pcap");
  std::ofstream(truncated, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()), 5000);
  std::size_t seen = 0;
  EXPECT_THROW(dump_vlp16_pcap(truncated, Vlp16Config{}, [&](const Vlp16Return&) { ++seen; }), PcapError);
  EXPECT_GT(seen, 0u);
  expect_error(truncated, "truncated");
}

}  // namespace
}  // namespace fsd
