// A start never aborts (issue 32): `fsd run` started from / (not the checkout) in every configuration either runs
// or exits 2 with a message naming the key or file; never a signal, never another status. The model and the
// dashboard are found beside the binary (a build tree) or under its install prefix.
#include <gtest/gtest.h>

#include <netinet/in.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "tests/scratch_dir.hpp"
#include "tests/truth_sources.hpp"

namespace fsd {
namespace {

namespace fs = std::filesystem;

std::string config(const std::string& name, const std::string& json) {
  const auto p = test::scratch_path(name);
  std::ofstream(p) << json;
  return p;
}

const std::string kTrack = fs::absolute("../shared/tracks/epfl_acceleration.csv").string();

// fsd (the build's, or `binary`) started from /: its exit status (-1: killed by a signal) and its output.
int from_root(const std::string& args, std::string& out, const std::string& binary = FSD_BINARY) {
  const std::string cmd = "cd / && " + binary + " " + args + " 2>&1";
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return -2;
  char buf[4096];
  out.clear();
  while (std::fgets(buf, sizeof buf, p)) out += buf;
  const int rc = pclose(p);
  return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}

TEST(StartAnywhere, EverySimulatorSourceRunsFromRoot) {
  for (const std::string source : {"truth", "lidar", "lidar_camera"}) {
    const auto cfg =
        config("root_" + source + ".json", R"({"run": {"perception_source": ")" + source + R"(", "max_sim_time": 2}})");
    std::string out;
    EXPECT_EQ(from_root("run --sim --headless --track " + kTrack + " --config " + cfg, out), 0) << source << "\n"
                                                                                                << out;
  }
}

TEST(StartAnywhere, TheDashboardIsServedFromRoot) {
  std::string out;
  const auto cfg = config("root_dash.json", test::truth_sources({{"run", {{"max_sim_time", 1}}}}));
  EXPECT_EQ(from_root("run --sim --port 0 --track " + kTrack + " --config " + cfg, out), 0) << out;
  EXPECT_NE(out.find("dashboard at http://"), std::string::npos) << out;
}

TEST(StartAnywhere, EveryStartErrorExitsTwoNamingWhatIsWrong) {
  struct Case {
    std::string what, args, names;
  };
  const auto missing_model = config("missing_model.json", R"({"run": {"perception_source": "lidar_camera"},
      "perception": {"camera": {"classifier": {"model": "/nonexistent/cone_model.json"}}}})");
  const auto bad_json = config("bad.json", "{\"run\": ");
  const auto bad_topics = config("bad_topics.json", R"({"dds": {"enabled": true, "topics": "cloud,radar"}})");
  const auto bad_peer = config("bad_peer.json", R"({"dds": {"enabled": true, "initial_peers": "car.local"}})");
  const Case cases[] = {
      {"missing model", "run --sim --headless --track " + kTrack + " --config " + missing_model,
       "/nonexistent/cone_model.json"},
      {"unreadable config", "run --sim --headless --config " + bad_json, "bad.json"},
      {"missing config", "run --sim --headless --config /nonexistent/fsd.json", "/nonexistent/fsd.json"},
      {"missing device", "run --headless", "drivers.vcu.device"},
      {"missing recording", "run --replay /nonexistent/run.mcap --headless", "/nonexistent/run.mcap"},
      {"track relative to the checkout", "run --sim --headless", "epfl_track_1.csv"},
      {"unknown dds topic", "run --sim --headless --track " + kTrack + " --config " + bad_topics, "dds.topics"},
      {"bad dds peer", "run --sim --headless --track " + kTrack + " --config " + bad_peer, "dds.initial_peers"},
      {"unknown role", "run --role driver", "--role"},
  };
  for (const auto& c : cases) {
    std::string out;
    EXPECT_EQ(from_root(c.args, out), 2) << c.what << "\n" << out;
    EXPECT_NE(out.find(c.names), std::string::npos) << c.what << ": the message does not name " << c.names << "\n"
                                                    << out;
  }
}

// A port held by another program: the dashboard's (TCP) and the perception role's LiDAR (UDP).
TEST(StartAnywhere, APortInUseExitsTwo) {
  const int tcp = ::socket(AF_INET, SOCK_STREAM, 0), udp = ::socket(AF_INET, SOCK_DGRAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ASSERT_EQ(::bind(tcp, reinterpret_cast<sockaddr*>(&a), sizeof a), 0);
  ASSERT_EQ(::listen(tcp, 1), 0);
  ASSERT_EQ(::bind(udp, reinterpret_cast<sockaddr*>(&a), sizeof a), 0);
  socklen_t len = sizeof a;
  ::getsockname(tcp, reinterpret_cast<sockaddr*>(&a), &len);
  const int tcp_port = ntohs(a.sin_port);
  ::getsockname(udp, reinterpret_cast<sockaddr*>(&a), &len);
  const int udp_port = ntohs(a.sin_port);
  const auto fast = config("port_fast.json", test::truth_sources({{"web", {{"bind", "127.0.0.1"}}}}));
  std::string out;
  EXPECT_EQ(from_root("run --sim --port " + std::to_string(tcp_port) + " --track " + kTrack + " --config " + fast, out),
            2)
      << out;
  EXPECT_NE(out.find(std::to_string(tcp_port)), std::string::npos) << out;
  const auto role = config("port_role.json", R"({"drivers": {"vlp16": {"address": "127.0.0.1", "data_port": )" +
                                                 std::to_string(udp_port) + "}}}");
  EXPECT_EQ(from_root("run --role perception --config " + role, out), 2) << out;
  EXPECT_NE(out.find("drivers.vlp16"), std::string::npos) << out;
  ::close(tcp);
  ::close(udp);
}

// An installed daemon: the binary in PREFIX/bin, its model under PREFIX/share/fsd. Found from / with the
// configuration's relative default; without the installed model, exit 2 naming it.
TEST(StartAnywhere, AnInstalledBinaryFindsItsModelUnderThePrefix) {
  const fs::path prefix = test::scratch_path("prefix");
  fs::create_directories(prefix / "bin");
  fs::copy_file(FSD_BINARY, prefix / "bin/fsd", fs::copy_options::overwrite_existing);
  const auto cfg = config("installed.json", R"({"run": {"perception_source": "lidar_camera", "max_sim_time": 1}})");
  const std::string args = "run --sim --headless --track " + kTrack + " --config " + cfg;
  std::string out;
  EXPECT_EQ(from_root(args, out, (prefix / "bin/fsd").string()), 2) << out;
  EXPECT_NE(out.find("perception/models/cone_hog_svm.json"), std::string::npos) << out;
  const fs::path model = prefix / "share/fsd/perception/models/cone_hog_svm.json";
  fs::create_directories(model.parent_path());
  fs::copy_file("perception/models/cone_hog_svm.json", model);
  EXPECT_EQ(from_root(args, out, (prefix / "bin/fsd").string()), 0) << out;
}

}  // namespace
}  // namespace fsd
