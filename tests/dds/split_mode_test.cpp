// Split mode (docs/dds.md): two fsd processes on loopback, the perception process (`fsd run --role perception`:
// the LiDAR and camera stages) and the driving one with the virtual car (`run.perception_source = dds`), finish a
// 2-lap trackdrive on the real pipeline with lap times within 2 % of the one-process run, both timed by the
// simulator's timekeeper (the scorecard's laps, measured on the truth).
#include <gtest/gtest.h>

#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <regex>
#include <string>

#include <nlohmann/json.hpp>

#include "tests/daemon/fsd_child.hpp"
#include "tests/dds/cyclone_reader.hpp"
#include "tests/scratch_dir.hpp"

namespace fsd {
namespace {

using namespace std::chrono_literals;

const std::string kTrack = "../shared/tracks/epfl_track_1.csv";

std::string write(const std::string& name, const std::string& json) {
  const auto p = test::scratch_path(name);
  std::ofstream(p) << json;
  return p;
}

nlohmann::json read_json(const std::string& path) {
  std::ifstream f(path);
  return nlohmann::json::parse(f, nullptr, false);
}

// A UDP port nobody uses now (the perception process's LiDAR port).
int free_udp_port() {
  const int s = ::socket(AF_INET, SOCK_DGRAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ::bind(s, reinterpret_cast<sockaddr*>(&a), sizeof a);
  socklen_t len = sizeof a;
  ::getsockname(s, reinterpret_cast<sockaddr*>(&a), &len);
  ::close(s);
  return ntohs(a.sin_port);
}

TEST(SplitMode, TwoProcessesOnLoopbackDriveTheTrackdriveAsOneDoes) {
  // The one-process run on the same pipeline (the LiDAR and camera stages), lockstep.
  const auto one_cfg = write("one.json", R"({"run": {"perception_source": "lidar_camera"}})");
  const auto one_report = test::scratch_path("one_report.json");
  test::Fsd one({"run", "--sim", "--headless", "--until-finished", "--track", kTrack, "--config", one_cfg, "--report",
                 one_report},
                test::scratch_path("one.log"));
  ASSERT_EQ(one.wait(600s), 0) << one.output();

  const int domain = test::test_domain();
  const int port = free_udp_port();
  const std::string dds = R"("dds": {"domain": )" + std::to_string(domain) + R"(, "initial_peers": "127.0.0.1")";
  const auto perception_cfg = write("perception.json", R"({"run": {"perception_source": "lidar_camera"},
          "drivers": {"vlp16": {"address": "127.0.0.1", "data_port": )" +
                                                           std::to_string(port) + "}}, " + dds + "}}");
  const auto driving_cfg = write("driving.json", R"({"run": {"perception_source": "dds"}, )" + dds +
                                                     R"(, "sim_lidar_port": )" + std::to_string(port) + "}}");
  test::Fsd perception({"run", "--role", "perception", "--config", perception_cfg}, test::scratch_path("perc.log"));
  ASSERT_FALSE(perception.wait_for(std::regex("perception role: "), 30s).empty()) << perception.output();
  const auto split_report = test::scratch_path("split_report.json");
  test::Fsd driving({"run", "--sim", "--headless", "--until-finished", "--track", kTrack, "--config", driving_cfg,
                     "--report", split_report},
                    test::scratch_path("driving.log"));
  const int rc = driving.wait(400s);
  perception.signal(SIGTERM);
  EXPECT_EQ(perception.wait(30s), 0) << perception.output();
  ASSERT_EQ(rc, 0) << driving.output() << "\n--- perception:\n" << perception.output();

  const auto one_r = read_json(one_report), split_r = read_json(split_report);
  ASSERT_EQ(one_r["laps"].size(), 2u) << one_r.dump();
  ASSERT_EQ(split_r["laps"].size(), 2u) << split_r.dump();
  EXPECT_EQ(split_r["verdict"], "pass") << split_r["verdict_reasons"].dump();
  EXPECT_EQ(split_r["cones_hit"], 0);
  EXPECT_EQ(split_r["perception"]["source"], "dds");
  for (int lap = 0; lap < 2; ++lap) {
    const double a = one_r["laps"][lap]["time_s"], b = split_r["laps"][lap]["time_s"];
    EXPECT_NEAR(b, a, 0.02 * a) << "lap " << lap + 1;
  }
  // The frames crossed: the driving side used what the perception process sent (its log's summary line).
  const std::regex used(R"(perception frames (\d+) received, (\d+) refused, (\d+) dropped, (\d+) used)");
  std::smatch m;
  const std::string log = driving.output();
  ASSERT_TRUE(std::regex_search(log, m, used)) << log;
  EXPECT_GT(std::stoi(m[4]), 500);  // 10 Hz over the two laps
  EXPECT_EQ(std::stoi(m[2]), 0);
}

}  // namespace
}  // namespace fsd
