// `fsd detect` as a user runs it: on the shared real VLP-16 capture (a ground plane that its lowest laser's
// returns lie on), on a capture the virtual car's VLP-16 wrote of cones at known places (found there, in the
// sensor's frame, with their colours close by), on the same cloud as CSV and as lidar-dump CSV, and on bad input
// (exit 2 with a message).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "drivers/sim/sensors/lidar_model.hpp"
#include "drivers/sim/sensors/pcap_writer.hpp"
#include "drivers/vlp16/pcap_dump.hpp"
#include "tests/daemon/fsd_process.hpp"
#include "tests/scratch_dir.hpp"
#include "tests/sim/world_test_util.hpp"

namespace fsd {
namespace {

struct Result {
  int status;
  std::string out;
};
Result run(const std::string& args) {
  Result r;
  r.status = test::run_fsd(args, &r.out);
  return r;
}

const char* kCapture = "../shared/data/vlp16/velodyne_vlp16.pcap";

TEST(DetectCli, TheRealCaptureHasAGroundPlaneItsLowestLaserLiesOn) {
  const auto r = run(std::string("detect --json --cloud ") + kCapture);
  ASSERT_EQ(r.status, 0) << r.out;
  const auto j = nlohmann::ordered_json::parse(r.out);
  // The contract's keys, in its order.
  ASSERT_EQ(j.size(), 2u);
  EXPECT_EQ(j.begin().key(), "cones");
  const auto& g = j.at("ground");
  EXPECT_EQ(std::vector<std::string>({g.begin().key(), std::next(g.begin()).key(), std::next(g.begin(), 2).key()}),
            (std::vector<std::string>{"a", "b", "h"}));
  for (const auto& c : j.at("cones")) {
    std::vector<std::string> keys;
    for (auto it = c.begin(); it != c.end(); ++it) keys.push_back(it.key());
    EXPECT_EQ(keys, (std::vector<std::string>{"x", "y", "z", "colour", "confidence", "points"}));
  }
  const double a = g.at("a"), b = g.at("b"), h = g.at("h");
  // The sensor sits 1.5-2 m above a road: a plane a few degrees from level below it.
  EXPECT_LT(h, -1.4);
  EXPECT_GT(h, -2.0);
  EXPECT_LT(std::atan(std::hypot(a, b)), deg2rad(5.0));
  // Independent check: the −15° laser's ground returns (its ring 5-8 m out; the returns nearer than 4.5 m are a
  // building's wall on the left) lie on the plane; a least-squares plane through them alone has 96 % within 10 cm.
  int on = 0, ring0 = 0;
  dump_vlp16_pcap(kCapture, Vlp16Config{}, [&](const Vlp16Return& ret) {
    if (ret.laser != 0 || ret.distance_m < 4.5) return;
    ++ring0;
    on += std::abs(ret.z - (a * ret.x + b * ret.y + h)) < 0.1;
  });
  ASSERT_GT(ring0, 1000);
  EXPECT_GT(on, ring0 * 85 / 100) << on << " of " << ring0;
}

// A capture of the virtual car standing at the origin (its VLP-16 on the nose, 0.35 m up) among hand-placed
// cones, with their true places in the sensor frame.
struct SimCapture {
  std::string pcap;
  std::vector<Vec3> cones_in_sensor;
  std::vector<ConeColour> colours;
};
SimCapture write_sim_capture() {
  using sim::test::make_cone;
  SimCapture c;
  std::vector<TrackCone> cones{make_cone(5.0, 1.5, ConeRole::Left),  make_cone(5.5, -1.5, ConeRole::Right),
                               make_cone(9.0, 1.6, ConeRole::Left),  make_cone(9.5, -1.6, ConeRole::Right),
                               make_cone(14.0, 1.7, ConeRole::Left), make_cone(-3.0, 2.5, ConeRole::Right)};
  const sim::World world(sim::test::make_track(cones), sim::test::bare_config(), 3);
  const sim::LidarConfig lc;
  const Pose3 mount = sim::lidar_mount(lc);
  for (const auto& k : world.cones()) {
    c.cones_in_sensor.push_back(mount.inverse() * k.base);
    c.colours.push_back(k.colour);
  }
  c.pcap = test::scratch_path("sim_cones.pcap");
  sim::PcapWriter w(c.pcap);
  sim::LidarModel lidar(lc, world, 7, 1000.0);
  lidar.advance_to(
      1000.25, [](Stamp) { return Pose3::Identity(); },
      [&](Stamp t, std::span<const std::uint8_t> p) { w.write(t, p); });
  return c;
}

// Every true cone found within 5 cm (on the ground plane: z at the base), nothing else; colours never wrong.
void expect_cones(const nlohmann::ordered_json& j, const SimCapture& truth, bool colours_close_by) {
  ASSERT_EQ(j.at("cones").size(), truth.cones_in_sensor.size()) << j.dump();
  for (std::size_t i = 0; i < truth.cones_in_sensor.size(); ++i) {
    const Vec3& t = truth.cones_in_sensor[i];
    const nlohmann::ordered_json* best = nullptr;
    double best_d = 1e9;
    for (const auto& c : j.at("cones")) {
      const double d = std::hypot(c.at("x").get<double>() - t.x(), c.at("y").get<double>() - t.y());
      if (d < best_d) best_d = d, best = &c;
    }
    ASSERT_NE(best, nullptr);
    EXPECT_LT(best_d, 0.05) << t.transpose();
    EXPECT_NEAR(best->at("z").get<double>(), t.z(), 0.02);
    const std::string colour = best->at("colour");
    if (colour != "unknown") {
      EXPECT_EQ(colour, to_string(truth.colours[i]));
    }
    if (colours_close_by && std::hypot(t.x(), t.y()) < 6.0) {
      EXPECT_EQ(colour, to_string(truth.colours[i]));
    }
  }
  EXPECT_NEAR(j.at("ground").at("h").get<double>(), -0.35, 0.01);
}

TEST(DetectCli, FindsTheVirtualCarsConesInItsCapture) {
  const SimCapture c = write_sim_capture();
  const auto r = run("detect --json --cloud " + c.pcap);
  ASSERT_EQ(r.status, 0) << r.out;
  expect_cones(nlohmann::ordered_json::parse(r.out), c, true);
  // The readable table names the cones too.
  const auto table = run("detect --cloud " + c.pcap);
  EXPECT_EQ(table.status, 0);
  EXPECT_NE(table.out.find("6 cone(s)"), std::string::npos) << table.out;
  EXPECT_NE(table.out.find("one revolution"), std::string::npos);
}

TEST(DetectCli, ReadsTheSameCloudAsCsvAndAsLidarDumpCsv) {
  const SimCapture c = write_sim_capture();
  const auto dump = run("lidar-dump --csv " + c.pcap);
  ASSERT_EQ(dump.status, 0);
  const std::string dump_csv = test::scratch_path("dump.csv");
  { std::ofstream(dump_csv) << dump.out; }
  const auto from_dump = run("detect --json --cloud " + dump_csv);
  ASSERT_EQ(from_dump.status, 0) << from_dump.out;
  expect_cones(nlohmann::ordered_json::parse(from_dump.out), c, true);

  // Plain x,y,z,intensity with a NaN row in it: dropped and counted, the same cones.
  std::istringstream in(dump.out);
  std::string line;
  std::getline(in, line);  // header
  std::ostringstream plain;
  plain << "nan,0,0,0\n";
  while (std::getline(in, line)) {
    std::vector<std::string> f;
    std::stringstream ls(line);
    for (std::string x; std::getline(ls, x, ',');) f.push_back(x);
    plain << f[5] << ',' << f[6] << ',' << f[7] << ',' << f[4] << '\n';
  }
  const std::string plain_csv = test::scratch_path("plain.csv");
  { std::ofstream(plain_csv) << plain.str(); }
  const auto from_plain = run("detect --json --cloud " + plain_csv);
  ASSERT_EQ(from_plain.status, 0) << from_plain.out;
  expect_cones(nlohmann::ordered_json::parse(from_plain.out), c, true);
  const auto table = run("detect --cloud " + plain_csv);
  EXPECT_NE(table.out.find("1 rows dropped"), std::string::npos) << table.out;
}

TEST(DetectCli, BadInputExitsTwoWithAMessage) {
  const auto write = [](const std::string& name, const std::string& text) {
    const std::string p = test::scratch_path(name);
    std::ofstream(p) << text;
    return p;
  };
  struct Case {
    std::string args, message;
  };
  const std::string huge = test::scratch_path("huge.csv");
  {
    std::ofstream(huge) << "1,2,3\n";
    std::filesystem::resize_file(huge, 300ull << 20);  // sparse: 10 M points' worth of bytes
  }
  const std::vector<Case> cases{
      {"detect --cloud /nonexistent.csv", "no such file"},
      {"detect --cloud " + write("empty.csv", ""), "no valid point"},
      {"detect --cloud " + write("nan.csv", "x,y,z\nnan,1,2\n3,nan,4\n"), "no valid point"},
      {"detect --cloud " + write("bad.csv", "1,2,3\n4,5\n"), ":2: expected 3 fields"},
      {"detect --cloud " + write("text.csv", "hello world\n"), "needs columns x, y and z"},
      {"detect --cloud " + huge, "bytes, more than"},
      {"detect --cloud " + write("notpcap.pcap", std::string("\xd4\xc3\xb2\xa1", 4) + "garbage"), ""},
      {"detect", "--cloud is required"},
      {"detect --cloud " + std::string(kCapture) + " --config /nonexistent.json", ""},
  };
  for (const auto& c : cases) {
    const auto r = run(c.args);
    EXPECT_EQ(r.status, 2) << c.args << "\n" << r.out;
    EXPECT_NE(r.out.find(c.message), std::string::npos) << c.args << "\n" << r.out;
  }
}

}  // namespace
}  // namespace fsd
