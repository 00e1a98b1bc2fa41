// `fsd run` on hardware interfaces, as a user runs it: the real binary against `fsd sim` in another process (VLP-16
// over loopback UDP, GNSS-INS and VCU on pseudo-terminals), or against pseudo-terminals this test plays itself.
// Ground truth is what the other end did: the virtual car's VCU stand-in owns the AS state and its sensors' rates
// are configured; the test's own VCU end decodes every Command the daemon sent.
#include <gtest/gtest.h>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <fstream>
#include <mutex>
#include <regex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/videoio.hpp>

#include "common/wire/vcu_protocol.hpp"
#include "daemon/feeders/hardware_run.hpp"
#include "daemon/feeders/hardware_stats.hpp"
#include "daemon/stack/gnss_state.hpp"
#include "drivers/serial/pseudo_terminal.hpp"
#include "drivers/sim/sensors/gnss_model.hpp"
#include "drivers/sim/vcu_standin.hpp"
#include "drivers/sim/vehicle/vehicle_truth.hpp"
#include "drivers/vlp16/pcap_reader.hpp"
#include "tests/daemon/telemetry/dashboard_client.hpp"
#include "tests/daemon/fsd_child.hpp"
#include "tests/daemon/fsd_process.hpp"
#include "tests/scratch_dir.hpp"

namespace fsd {
namespace {

using namespace std::chrono_literals;
using Clock = std::chrono::steady_clock;

using test::scratch_path;

std::string slurp(const std::string& path) {
  std::ifstream f(path);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

using test::Fsd;

// A UDP port nobody uses right now on the loopback (the kernel picks it).
int free_udp_port() {
  const int s = ::socket(AF_INET, SOCK_DGRAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ::bind(s, reinterpret_cast<sockaddr*>(&a), sizeof a);
  socklen_t n = sizeof a;
  ::getsockname(s, reinterpret_cast<sockaddr*>(&a), &n);
  ::close(s);
  return ntohs(a.sin_port);
}

// Plays the shared VLP-16 capture's data packets to 127.0.0.1:port over and over (about a revolution each time,
// at the sensor's 754 packets/s) until stopped: the real sensor's bytes for the daemon's receiver.
class Vlp16Replayer {
 public:
  // Data packets to `port`; the capture's position packets (UDP 8308 in the file) to `position_port` if given.
  explicit Vlp16Replayer(int port, int position_port = 0)
      : thread_([this, port, position_port] { loop(port, position_port); }) {}
  ~Vlp16Replayer() {
    done_ = true;
    thread_.join();
  }

 private:
  void loop(int port, int position_port) {
    std::vector<std::pair<std::vector<std::uint8_t>, int>> packets;  // payload, destination port
    {
      PcapReader pcap("../shared/data/vlp16/velodyne_vlp16.pcap", {2368, 8308});
      UdpDatagram d;
      while (pcap.next(d))
        if (d.dst_port == 2368 || position_port > 0)
          packets.emplace_back(std::vector<std::uint8_t>(d.payload.begin(), d.payload.end()),
                               d.dst_port == 2368 ? port : position_port);
    }
    const int s = ::socket(AF_INET, SOCK_DGRAM, 0);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    for (int round = 0; round < 600 && !done_; ++round)  // at most a minute
      for (const auto& [p, to] : packets) {
        if (done_) break;
        a.sin_port = htons(static_cast<std::uint16_t>(to));
        ::sendto(s, p.data(), p.size(), 0, reinterpret_cast<const sockaddr*>(&a), sizeof a);
        std::this_thread::sleep_for(std::chrono::microseconds(1326));
      }
    ::close(s);
  }
  std::atomic<bool> done_{false};
  std::thread thread_;
};

std::string write_file(const std::string& name, const std::string& text) {
  const std::string path = scratch_path(name);
  std::ofstream(path) << text;
  return path;
}

// `fsd sim` playing the car in another process: its VLP-16 on a free loopback port, its GNSS-INS and VCU on
// pseudo-terminals, its RES pressing go `res_go_at_s` after Ready (< 0: never); and the `fsd run` config that drives
// it over them. Every watchdog of both ends (VCU heartbeat and link, the supervisor's VCU and pose) is at 1 s: a
// loaded 2-core machine stalls the real-time sim and the daemon for a hundred ms at times; these tests are about the
// wiring, the watchdogs are tested in test_control and test_drivers.
struct CarInAnotherProcess {
  int port = free_udp_port();
  Fsd sim;
  std::string gnss, vcu;
  CarInAnotherProcess(const std::string& name, const std::string& track, double res_go_at_s)
      : sim({"sim", "--config",
             write_file(name + "_sim.json",
                        nlohmann::json{{"sim",
                                        {{"enable_camera", false},
                                         {"vcu",
                                          {{"ready_to_drive_s", 1.0},
                                           {"res_go_at_s", res_go_at_s},
                                           {"heartbeat_timeout", 1.0}}}}},
                                       {"drivers", {{"vlp16", {{"data_port", port}}}}}}
                            .dump()),
             "--track", track, "--duration", "120"},
            scratch_path(name + "_sim.log")) {
    gnss = sim.wait_for(std::regex("GNSS-INS NMEA on (\\S+)"), 30s);
    vcu = sim.wait_for(std::regex("VCU link on (\\S+)"), 5s);
  }
  bool up() const { return !gnss.empty() && !vcu.empty(); }
  // The `fsd run` config, with `patch` merged in (a JSON merge patch).
  std::string run_config(const std::string& name, const nlohmann::json& patch = nlohmann::json::object()) {
    nlohmann::json cfg{
        {"drivers",
         {{"vcu", {{"device", vcu}, {"timeout", 1.0}}},
          {"gnss", {{"device", gnss}}},
          {"vlp16", {{"address", "127.0.0.1"}, {"data_port", port}, {"position_port", free_udp_port()}}}}},
        {"control", {{"supervisor", {{"vcu_timeout", 1.0}, {"pose_timeout", 1.0}}}}},
        {"web", {{"bind", "127.0.0.1"}, {"port", 0}}}};
    cfg.merge_patch(patch);
    return write_file(name + "_run.json", cfg.dump());
  }
};

// Hand-computed: 2 m/s along a course 0.1 rad left of the heading is vx = 2 cos 0.1, vy = 2 sin 0.1.
TEST(GnssState, BodyVelocityFromSpeedCourseAndHeading) {
  GnssSample s;
  s.stamp = 12.5;
  s.enu = Vec3(3.0, -4.0, 0.2);
  s.heading = 1.2;
  s.course = 1.3;
  s.speed = 2.0;
  s.velocity_valid = true;
  s.yaw_rate = 0.25;
  s.yaw_rate_valid = true;
  const VehicleState v = state_from_gnss(s, -0.05);
  EXPECT_EQ(v.stamp, 12.5);
  EXPECT_DOUBLE_EQ(v.pose.x, 3.0);
  EXPECT_DOUBLE_EQ(v.pose.y, -4.0);
  EXPECT_DOUBLE_EQ(v.pose.yaw, 1.2);
  EXPECT_NEAR(v.vx, 1.9900083305, 1e-9);
  EXPECT_NEAR(v.vy, 0.1996668332, 1e-9);
  EXPECT_EQ(v.yaw_rate, 0.25);
  EXPECT_EQ(v.steering, -0.05);

  s.velocity_valid = false;  // no VTG/RMC in the epoch: no velocity rather than a stale one
  s.yaw_rate_valid = false;
  const VehicleState w = state_from_gnss(s, 0.0);
  EXPECT_EQ(w.vx, 0.0);
  EXPECT_EQ(w.vy, 0.0);
  EXPECT_EQ(w.yaw_rate, 0.0);
}

TEST(GnssState, PoseNeedsFixHeadingAndOrigin) {
  GnssSample s;
  s.fix_quality = 1;
  s.heading_valid = true;
  EXPECT_TRUE(gnss_pose_usable(s, true));
  EXPECT_FALSE(gnss_pose_usable(s, false));
  s.fix_quality = 0;
  EXPECT_FALSE(gnss_pose_usable(s, true));
  s.fix_quality = 4;
  s.heading_valid = false;
  EXPECT_FALSE(gnss_pose_usable(s, true));
}

// Rates over the period between two snapshots, error counters as totals.
TEST(HardwareStats, RatesLineFromTwoSnapshots) {
  HardwareCounters a, b;
  a.t = 10.0;
  b.t = 12.0;
  a.lidar.udp.datagrams = 100;
  b.lidar.udp.datagrams = 100 + 2 * 754;
  b.lidar.scans = 20;
  b.lidar.udp.kernel_drops = 7;
  a.gnss.nmea.samples = 5;
  b.gnss.nmea.samples = 105;
  b.gnss.nmea.good_samples = 90;
  b.gnss.nmea.bad_checksum = 3;
  b.vcu.session.statuses = 200;
  b.vcu.session.commands_sent = 198;
  b.control_cycles = 200;
  const std::string line = rates_line(a, b);
  EXPECT_NE(line.find("lidar 754 pkt/s 10.0 scan/s [kernel drops 7,"), std::string::npos) << line;
  EXPECT_NE(line.find("position 0.0 pkt/s PPS absent [rejected 0]"), std::string::npos) << line;
  b.lidar.position_udp.datagrams = 2;
  b.lidar.pps = PpsState::Locked;
  EXPECT_NE(rates_line(a, b).find("position 1.0 pkt/s PPS locked"), std::string::npos) << rates_line(a, b);
  EXPECT_NE(line.find("gnss 50.0 Hz, good 45.0 Hz [bad checksum 3,"), std::string::npos) << line;
  EXPECT_NE(line.find("vcu status 100 Hz, command 99 Hz"), std::string::npos) << line;
  EXPECT_EQ(line.find("camera"), std::string::npos) << line;  // none configured
  EXPECT_NE(line.find("control 100 Hz"), std::string::npos) << line;
  b.camera = CameraStats{};
  b.camera->frames = 40;
  EXPECT_NE(rates_line(a, b).find("camera 20.0 fps"), std::string::npos);
}

TEST(HardwareRun, MissingDeviceExitsTwoNamingKeyAndPath) {
  const std::string vcu_missing =
      write_file("hw_missing_vcu.json", R"({"drivers": {"vcu": {"device": "/nonexistent/ttyVCU_test"}}})");
  Fsd a({"run", "--config", vcu_missing, "--mission", "inspection"}, scratch_path("missing_vcu.log"));
  EXPECT_EQ(a.wait(20s), 2);
  EXPECT_NE(a.output().find("drivers.vcu.device: no such device '/nonexistent/ttyVCU_test'"), std::string::npos)
      << a.output();

  PseudoTerminal vcu;  // a VCU that is there, so the GNSS-INS device is the one found missing
  const std::string gnss_missing =
      write_file("hw_missing_gnss.json", R"({"drivers": {"vcu": {"device": ")" + vcu.slave_path() +
                                             R"("}, "gnss": {"device": "/nonexistent/ttyGNSS_test"}}})");
  Fsd b({"run", "--config", gnss_missing, "--mission", "inspection"}, scratch_path("missing_gnss.log"));
  EXPECT_EQ(b.wait(20s), 2);
  EXPECT_NE(b.output().find("drivers.gnss.device: no such device '/nonexistent/ttyGNSS_test'"), std::string::npos)
      << b.output();

  // A regular file is not a serial port.
  const std::string not_tty = write_file("hw_not_a_tty", "");
  const std::string cfg = write_file("hw_not_tty.json", R"({"drivers": {"vcu": {"device": ")" + not_tty + R"("}}})");
  Fsd c({"run", "--config", cfg, "--mission", "inspection"}, scratch_path("not_tty.log"));
  EXPECT_EQ(c.wait(20s), 2);
  EXPECT_NE(c.output().find("is not a character device"), std::string::npos) << c.output();
}

// A mission that needs cones, on the car's own perception: fsd sim plays the car on the acceleration layout (its
// LiDAR over UDP, GNSS-INS and VCU over ptys), fsd run finds the lane with its LiDAR stages and drives it. The
// truth is fsd sim's: the cones it counts as hit, and how far the car went from the start.
TEST(HardwareRun, AccelerationOnItsOwnLidarAgainstFsdSim) {
  CarInAnotherProcess car("hw_acc", "../shared/tracks/epfl_acceleration.csv", 1.5);
  ASSERT_TRUE(car.up()) << car.sim.output();
  const std::string run_cfg = car.run_config("hw_acc");
  const std::string report_path = scratch_path("hw_acc_report.json");
  std::remove(report_path.c_str());
  Fsd run({"run", "--config", run_cfg, "--mission", "acceleration", "--until-finished", "--report", report_path},
          scratch_path("hw_acc_run.log"));
  const int rc = run.wait(90s);
  const std::string log = run.output();
  car.sim.signal(SIGTERM);
  const std::string hit = car.sim.wait_for(std::regex("LiDAR packets in \\S+ s, (\\d+) cone\\(s\\) hit"), 20s);
  EXPECT_EQ(car.sim.wait(20s), 0);
  ASSERT_EQ(rc, 0) << log;
  EXPECT_NE(log.find("run.perception_source = lidar_camera without the camera's calibration"), std::string::npos) << log;
  const auto r = nlohmann::json::parse(slurp(report_path));
  EXPECT_EQ(r["as_state"], "Finished");
  EXPECT_TRUE(r["mission_succeeded"]);
  // The 75 m lane driven and the stop inside the rules' 100 m after it (the layout's lane is 75 m).
  EXPECT_GT(r["max_distance_from_start_m"].get<double>(), 75.0);
  EXPECT_LT(r["max_distance_from_start_m"].get<double>(), 175.0);
  ASSERT_FALSE(hit.empty()) << car.sim.output();
  EXPECT_EQ(std::stoi(hit), 0) << car.sim.output();
}

// The inspection mission end to end: fsd sim plays the car (its VCU stand-in owns the AS state and moves the car
// on the daemon's Commands), fsd run drives it over the real transports until AS Finished.
TEST(HardwareRun, InspectionAgainstFsdSimGoesReadyDrivingFinished) {
  CarInAnotherProcess car("hw", "../shared/tracks/epfl_track_1.csv", 1.5);
  ASSERT_TRUE(car.up()) << car.sim.output();
  constexpr double kInspection = 3.0;  // s of steering sweep at control.mission.inspection_speed (1 m/s)
  const std::string run_cfg = car.run_config(
      "hw", {{"control", {{"mission", {{"inspection_duration", kInspection}}}}}, {"run", {{"stats_period", 1.0}}}});
  const std::string report_path = scratch_path("hw_report.json");
  const std::string recording = scratch_path("hw_run.mcap");
  std::remove(report_path.c_str());
  Fsd run({"run", "--config", run_cfg, "--mission", "inspection", "--until-finished", "--report", report_path,
           "--record", recording},
          scratch_path("hw_run.log"));
  const int rc = run.wait(90s);
  const std::string log = run.output();
  car.sim.signal(SIGTERM);
  EXPECT_EQ(car.sim.wait(20s), 0);
  ASSERT_EQ(rc, 0) << log;

  const auto r = nlohmann::json::parse(slurp(report_path));
  EXPECT_EQ(r["mode"], "hardware");
  EXPECT_EQ(r["mission"], "inspection");
  EXPECT_EQ(r["as_state"], "Finished");
  EXPECT_EQ(r["ended_by"], "finished");
  EXPECT_TRUE(r["mission_succeeded"]);
  // The stand-in's state machine, as its Status frames reported it: exactly Off → Ready → Driving → Finished.
  std::vector<std::string> states;
  for (const auto& t : r["as_transitions"])
    states.push_back(t["from"].get<std::string>() + ">" + t["to"].get<std::string>());
  EXPECT_EQ(states, (std::vector<std::string>{"Off>Ready", "Ready>Driving", "Driving>Finished"})) << r.dump(2);
  // The RES go came ≥ ready_to_drive_s after Ready; the sweep lasted inspection_duration before the stop.
  const auto& tr = r["as_transitions"];
  ASSERT_EQ(tr.size(), 3u);
  EXPECT_GE(tr[1]["t"].get<double>() - tr[0]["t"].get<double>(), 1.0);
  EXPECT_GE(tr[2]["t"].get<double>() - tr[1]["t"].get<double>(), kInspection);
  EXPECT_LT(tr[2]["t"].get<double>() - tr[1]["t"].get<double>(), kInspection + 10.0);
  // The car moved on the daemon's commands: about 1 m/s for 3 s, seen by the GNSS-INS.
  EXPECT_GT(r["max_distance_from_start_m"].get<double>(), 1.0);
  EXPECT_LT(r["max_distance_from_start_m"].get<double>(), 6.0);

  // Every stream arrived at about the virtual car's rates (VLP-16 at 600 rpm: 754 packets/s; GNSS-INS 50 Hz;
  // VCU Status 100 Hz), all of it valid. Loose bounds: a loaded machine slows the real-time sim.
  const double wall = r["wall_time_s"];
  const auto& d = r["drivers"];
  const auto lidar = d["vlp16"]["datagrams"].get<double>();
  EXPECT_GT(lidar, 0.4 * 754 * wall) << d.dump(2);
  EXPECT_LT(lidar, 1.1 * 754 * wall);
  EXPECT_EQ(d["vlp16"]["packets"], d["vlp16"]["datagrams"]);
  EXPECT_EQ(d["vlp16"]["rejected"], 0);
  EXPECT_GT(d["vlp16"]["scans"].get<double>(), 0.4 * 10 * wall);
  EXPECT_GT(d["gnss"]["samples"].get<double>(), 0.4 * 50 * wall) << d.dump(2);
  EXPECT_LT(d["gnss"]["samples"].get<double>(), 1.1 * 50 * wall);
  EXPECT_EQ(d["gnss"]["bad_checksum"], 0);
  EXPECT_GT(d["vcu"]["statuses"].get<double>(), 0.4 * 100 * wall);
  EXPECT_EQ(d["vcu"]["rejected"], 0);
  EXPECT_GT(d["vcu"]["commands_sent"].get<double>(), 0.4 * 100 * wall);
  EXPECT_EQ(d["control"]["overruns"].get<double>() < 0.2 * d["control"]["cycles"].get<double>(), true);

  // The sim sent at least what the daemon received.
  const std::string sent = car.sim.wait_for(std::regex("fsd sim: (\\d+) LiDAR packets"), 5s);
  ASSERT_FALSE(sent.empty()) << car.sim.output();
  EXPECT_GE(std::stod(sent), lidar);
  // The log shows the per-driver rates and the transitions.
  EXPECT_NE(log.find("pkt/s"), std::string::npos) << log;
  EXPECT_NE(log.find("AS Ready -> Driving"), std::string::npos) << log;

  // The run was recorded as the control thread fed it (nothing dropped at these rates), and replays headless
  // through the same stack: the frames and cycles the recorder wrote, the VCU's recorded statuses taking the AS
  // through the same states, and the commands the live stack computed.
  const auto& rec = r["recording"];
  EXPECT_EQ(rec["dropped"], 0) << rec.dump(2);
  EXPECT_EQ(rec["error"], "");
  EXPECT_EQ(rec["cycles_written"], d["control"]["cycles"]);
  const std::string replay_path = scratch_path("hw_replay.json");
  std::string replay_log;
  ASSERT_EQ(test::run_fsd("run --replay " + recording + " --headless --report " + replay_path, &replay_log), 0)
      << replay_log;
  const auto p = nlohmann::json::parse(slurp(replay_path));
  EXPECT_EQ(p["mode"], "replay");
  EXPECT_EQ(p["mission"], "inspection");
  EXPECT_EQ(p["as_state"], "Finished");
  EXPECT_EQ(p["replay"]["recorded_mode"], "car");
  EXPECT_EQ(p["replay"]["frames"], rec["frames_written"]);
  EXPECT_EQ(p["replay"]["cycles"], rec["cycles_written"]);
  EXPECT_EQ(p["replay"]["commands_compared"], rec["commands_written"]);
  EXPECT_EQ(p["replay"]["command_mismatches"], 0) << p["replay"].dump(2);
}

// SIGTERM mid-run, while driving: the daemon exits 0 and the last Commands the VCU sees are safe ones (speed 0,
// brake). This test plays both devices with the virtual car's models, the car standing at the origin: the GNSS-INS
// on one pseudo-terminal, the VCU stand-in (RES go 0.3 s after Ready) on the other, and it decodes every Command.
class Devices {
 public:
  Devices() : vcu_standin_(standin_config(), [this](Stamp, std::span<const std::uint8_t> b) { vcu_.write(b); }) {
    thread_ = std::thread([this] { loop(); });
  }
  ~Devices() {
    done_ = true;
    thread_.join();
  }
  const PseudoTerminal& vcu() const { return vcu_; }
  const PseudoTerminal& gnss() const { return gnss_; }
  std::vector<wire::vcu::Command> commands() const {
    std::lock_guard lock(m_);
    return commands_;
  }
  AsState as_state() const {
    std::lock_guard lock(m_);
    return vcu_standin_.state();
  }

 private:
  static sim::VcuStandinConfig standin_config() {
    sim::VcuStandinConfig c;
    c.ready_to_drive_s = 0.2;
    c.res_go_at_s = 0.3;
    c.heartbeat_timeout = 1.0;  // a loaded machine may stall the daemon's sender for a few hundred ms
    return c;
  }
  void loop() {
    wire::vcu::Decoder decoder(
        {[this](const wire::vcu::Command& c, std::uint16_t) { commands_.push_back(c); }, nullptr, nullptr});
    sim::GnssModel gnss_model(sim::GnssModelConfig{}, 7);
    std::array<std::uint8_t, 1024> buf{};
    const auto t0 = Clock::now();
    while (!done_) {
      const std::size_t n = vcu_.read(buf, 0.002);
      const Stamp t = std::chrono::duration<double>(Clock::now() - t0).count();
      sim::VehicleTruth truth;
      truth.t = t;
      {
        std::lock_guard lock(m_);
        if (n) {
          decoder.feed(std::span(buf.data(), n));
          vcu_standin_.feed(t, std::span(buf.data(), n));
        }
        vcu_standin_.step(t, truth);
      }
      gnss_model.advance_to(
          t,
          [](Stamp at) {
            sim::VehicleTruth standing;
            standing.t = at;
            return standing;
          },
          [this](Stamp, std::span<const std::uint8_t> b) { gnss_.write(b); });
    }
  }

  PseudoTerminal vcu_, gnss_;
  mutable std::mutex m_;
  sim::VcuStandin vcu_standin_;               // guarded by m_
  std::vector<wire::vcu::Command> commands_;  // guarded by m_
  std::atomic<bool> done_{false};
  std::thread thread_;
};

// The daemon killed (SIGKILL, no safe stop) while the car stands in AS Ready, then started again: fsd sim's VCU
// stand-in fires the EBS when the heartbeat stops (the rules' AS Emergency), and the restarted stack names that
// state and its cause as a fault, asks for nothing and drives nothing. The VCU's own log is the truth.
TEST(HardwareRun, KilledWhileStandingTheRestartedStackNamesTheEmergencyAndDrivesNothing) {
  CarInAnotherProcess car("hw_restart", "../shared/tracks/epfl_track_1.csv", -1.0);  // the RES never says go
  ASSERT_TRUE(car.up()) << car.sim.output();
  const std::string run_cfg = car.run_config("hw_restart");
  {
    Fsd first({"run", "--config", run_cfg, "--mission", "trackdrive"}, scratch_path("hw_restart_first.log"));
    ASSERT_FALSE(car.sim.wait_for(std::regex("VCU AS Off \\S+ Ready at"), 60s).empty()) << car.sim.output() << first.output();
    first.signal(SIGKILL);
    EXPECT_EQ(first.wait(10s), 128 + SIGKILL);
  }
  ASSERT_FALSE(car.sim.wait_for(std::regex("VCU AS Ready \\S+ Emergency at \\S+ s: heartbeat lost"), 10s).empty())
      << car.sim.output();

  const std::string report_path = scratch_path("hw_restart_report.json");
  std::remove(report_path.c_str());
  Fsd again({"run", "--config", run_cfg, "--mission", "trackdrive", "--report", report_path},
            scratch_path("hw_restart_again.log"));
  const std::string what = again.wait_for(std::regex("fault at t = \\S+ s: vcu: (AS Emergency: [^>]*) ->"), 30s);
  EXPECT_NE(what.find("heartbeat was lost"), std::string::npos) << again.output();
  std::this_thread::sleep_for(2s);  // a while longer: nothing may be asked for
  again.signal(SIGTERM);
  ASSERT_EQ(again.wait(20s), 0) << again.output();
  const auto r = nlohmann::json::parse(slurp(report_path));
  EXPECT_EQ(r["as_state"], "Emergency");
  ASSERT_FALSE(r["faults"].empty());
  EXPECT_EQ(r["faults"][0]["source"], "vcu") << r["faults"].dump();
  car.sim.signal(SIGTERM);
  EXPECT_EQ(car.sim.wait(20s), 0);
  // The VCU's log: Ready, then the EBS on the lost heartbeat, and no transition after it (nothing was asked for).
  const std::string sim_log = car.sim.output();
  const std::regex transition("VCU AS \\S+ \\S+ \\S+ at");
  const auto n = std::distance(std::sregex_iterator(sim_log.begin(), sim_log.end(), transition), std::sregex_iterator());
  EXPECT_EQ(n, 2) << sim_log;
}

// The camera is a looping 160×120 video file at 20 fps. The pit-lane dashboard runs as on the car (no --headless):
// while driving, a browser's view of it shows the stack's AS state and mission, the camera's picture, and /metrics
// the control loop.
TEST(HardwareRun, SigtermWhileDrivingEndsWithSafeStopCommands) {
  Devices dev;
  const std::string video = scratch_path("hw_camera.avi");
  {
    cv::VideoWriter w(video, cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), 20.0, cv::Size(160, 120));
    if (!w.isOpened()) GTEST_SKIP() << "this OpenCV cannot write MJPG/AVI";
    for (int k = 0; k < 10; ++k) w.write(cv::Mat(120, 160, CV_8UC3, cv::Scalar::all(20 * k)));
  }
  const int lidar_port = free_udp_port(), position_port = free_udp_port();
  const std::string cfg =
      write_file("hw_sigterm.json",
                 R"({"drivers": {"vcu": {"device": ")" + dev.vcu().slave_path() + R"("}, "gnss": {"device": ")" +
                     dev.gnss().slave_path() + R"("}, "vlp16": {"address": "127.0.0.1", "data_port": )" +
                     std::to_string(lidar_port) + R"(, "position_port": )" + std::to_string(position_port) +
                     R"(},
                      "camera": {"enabled": true, "source": ")" +
                     video + R"(", "width": 160, "height": 120,
                                 "fps": 20, "loop_file": true}},
          "car": {"lidar": {"x": 1.5, "z": 0.8, "yaw": 0.1}},
          "control": {"supervisor": {"vcu_timeout": 1.0, "pose_timeout": 1.0}}, "run": {"stats_period": 0.5},
          "web": {"bind": "127.0.0.1", "port": 0}})");
  const std::string report_path = scratch_path("hw_sigterm_report.json");
  std::remove(report_path.c_str());
  const auto driving_commands = [&] {
    const auto c = dev.commands();
    return std::count_if(c.begin(), c.end(), [](const auto& k) { return k.target_speed > 0 && !k.brake_hard; });
  };

  Fsd run({"run", "--config", cfg, "--mission", "inspection", "--report", report_path}, scratch_path("hw_sigterm.log"));
  const auto t0 = Clock::now();
  while (driving_commands() < 30 && Clock::now() - t0 < 30s) std::this_thread::sleep_for(20ms);
  ASSERT_GE(driving_commands(), 30) << run.output();
  ASSERT_EQ(dev.as_state(), AsState::Driving);

  const std::string port_text = run.wait_for(std::regex("dashboard at http://127\\.0\\.0\\.1:(\\d+)/"), 5s);
  ASSERT_FALSE(port_text.empty()) << run.output();
  const auto port = static_cast<std::uint16_t>(std::stoi(port_text));
  const auto state = web::test::http_request(port, boost::beast::http::verb::get, "/api/state");
  ASSERT_EQ(state.status, 200u) << state.body;
  const auto sj = nlohmann::json::parse(state.body);
  EXPECT_EQ(sj["as_state"], "Driving") << state.body;
  EXPECT_EQ(sj["mission"], "inspection");
  EXPECT_EQ(sj["vehicle"]["target_speed"], 1.0);  // control.mission.inspection_speed
  const auto metrics = web::test::http_request(port, boost::beast::http::verb::get, "/metrics");
  ASSERT_EQ(metrics.status, 200u);
  const auto m = test::parse_metrics(metrics.body);
  EXPECT_GT(m.at("fsd_control_cycles_total"), 30);
  EXPECT_EQ(m.at("fsd_as_state"), 2);  // Driving
  EXPECT_GT(m.at("fsd_telemetry_snapshots_total"), 0);
  {
    test::WsClient browser(port);
    ASSERT_TRUE(browser.handshake_ok());
    const auto subs = test::subscribe(browser, {"/camera/image"});
    ASSERT_EQ(subs.size(), 1u);
    const auto image = test::next_on(browser, subs.at("/camera/image"));
    ASSERT_TRUE(image);
    EXPECT_EQ((*image)["format"], "jpeg");
    // A 160×120 JPEG, base64: a few hundred bytes at least.
    const std::string b64 = (*image)["data"];
    EXPECT_GT(b64.size(), 200u);
  }
  {
    // The real capture's points on the dashboard, on the car standing at the GNSS origin heading east (the
    // stand-in's truth, RTK noise of 2 cm). Once perception has run on a scan the cloud is its split (ground and
    // obstacles) in the vehicle frame, drawn at the car's pose; before that the raw scan at the configured mount:
    // 1.5 m ahead, 0.8 m up, yawed 0.1 rad. Both must be placed right, and perception must run on the real capture.
    Vlp16Replayer lidar(lidar_port, position_port);
    test::WsClient browser(port);
    ASSERT_TRUE(browser.handshake_ok());
    const auto subs = test::subscribe(browser, {"/lidar/points"});
    ASSERT_EQ(subs.size(), 1u);
    bool perceived = false;
    for (int k = 0; k < 20 && !perceived; ++k) {
      const auto cloud = test::next_on(browser, subs.at("/lidar/points"), 10s);
      ASSERT_TRUE(cloud) << run.output();
      const auto& pos = (*cloud)["pose"]["position"];
      const auto& q = (*cloud)["pose"]["orientation"];
      const double yaw = 2.0 * std::atan2(q["z"].get<double>(), q["w"].get<double>());
      perceived = pos["z"].get<double>() == 0.0;
      const double x = perceived ? 0.0 : 1.5, z = perceived ? 0.0 : 0.8, heading = perceived ? 0.0 : 0.1;
      EXPECT_NEAR(pos["x"].get<double>(), x, 0.2);
      EXPECT_NEAR(pos["y"].get<double>(), 0.0, 0.2);
      EXPECT_NEAR(pos["z"].get<double>(), z, 1e-9);
      EXPECT_NEAR(yaw, heading, 0.05);
      // Thousands of 16-byte points (a revolution has about 19.6 k valid ones; perception keeps its 20 m box).
      EXPECT_GT((*cloud)["data"].get<std::string>().size(), 4u * 1000 * 16 / 3);
    }
    EXPECT_TRUE(perceived) << "no cloud from perception on the real capture";
  }
  run.signal(SIGTERM);
  const int rc = run.wait(10s);
  std::this_thread::sleep_for(200ms);  // the last frames in flight
  EXPECT_EQ(rc, 0) << run.output();

  const auto commands = dev.commands();
  ASSERT_GE(commands.size(), 33u);
  // The inspection sweep was under way (control.mission.inspection_speed 1 m/s) with the mission selected...
  const auto& last_driving =
      *std::find_if(commands.rbegin(), commands.rend(), [](const auto& k) { return k.target_speed > 0; });
  EXPECT_EQ(last_driving.target_speed, 1.0);
  EXPECT_FALSE(last_driving.brake_hard);
  EXPECT_EQ(last_driving.mission, Mission::Inspection);
  // ...and the end is drivers.vcu.stop_frames (3) safe Commands, nothing after them.
  for (std::size_t i = commands.size() - 3; i < commands.size(); ++i) {
    EXPECT_EQ(commands[i].target_speed, 0.0) << i;
    EXPECT_TRUE(commands[i].brake_hard) << i;
  }
  const std::string out = run.output();
  EXPECT_NE(out.find("AS Ready -> Driving"), std::string::npos) << out;
  EXPECT_NE(out.find("stopping (signal)"), std::string::npos) << out;
  EXPECT_NE(out.find("VCU link stopped after 3 safe commands"), std::string::npos) << out;
  // No ground truth on the car: the default truth source runs the perception stages (no camera calibration here).
  EXPECT_NE(out.find("run.perception_source = lidar_camera without the camera's calibration"), std::string::npos) << out;

  // Without --until-finished a signal is a normal end; the camera delivered its frames at about 20 fps.
  const auto r = nlohmann::json::parse(slurp(report_path));
  EXPECT_EQ(r["ended_by"], "signal");
  EXPECT_EQ(r["as_state"], "Driving");
  const auto& cam = r["drivers"]["camera"];
  ASSERT_TRUE(cam.is_object()) << r.dump(2);
  EXPECT_GT(cam["frames"].get<double>(), 0.3 * 20 * r["wall_time_s"].get<double>()) << cam.dump();
  EXPECT_EQ(cam["size_mismatches"], 0);
  EXPECT_NE(out.find("camera "), std::string::npos) << out;
  EXPECT_NE(out.find(" fps [dropped"), std::string::npos) << out;
  // The capture's position packets reached their own port: accepted, PPS absent and no GPS sentence in them
  // (as `fsd lidar-dump` reads the file: 16 of 16 with NMEA absent).
  const auto& pos = r["drivers"]["vlp16"]["position"];
  ASSERT_TRUE(pos.is_object()) << r.dump(2);
  EXPECT_GT(pos["packets"].get<int>(), 0) << pos.dump();
  EXPECT_EQ(pos["packets"], pos["datagrams"]);
  EXPECT_EQ(pos["rejected"], 0);
  EXPECT_EQ(pos["pps"], "absent");
  EXPECT_EQ(pos["nmea_absent"], pos["packets"]);
  EXPECT_NE(out.find("position "), std::string::npos) << out;
}

}  // namespace
}  // namespace fsd
