// The DDS bridge's cost to the control loop and the cloud topic's throughput and latency (docs/benchmarks.md).
//
//   build/bench/dds_bench [seconds]
//
// 1. The control loop: `fsd run --sim` in real time (SimRun, the virtual car on its LiDAR, truth sources), once with
//    DDS off and once with dds.enabled and a reader of every topic in another participant of this process; the
//    period between the ends of two cycles (the loop hook) and its p50/p99/max.
// 2. The cloud: sensor_msgs/PointCloud2 of a VLP-16 scan's size written at 10 Hz (latency: write to the reader's
//    callback, stamped in the message) and back to back for 2 s (throughput, what arrived), between two
//    participants with Fast DDS's intra-process delivery off: through its transports, as between two processes.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <thread>
#include <vector>

#include <fastrtps/xmlparser/XMLProfileManager.h>
#include <fastdds/dds/subscriber/SampleInfo.hpp>
#include <nlohmann/json.hpp>

#include "common/config.hpp"
#include "common/logging.hpp"
#include "daemon/dds/dds_participant.hpp"
#include "daemon/dds/ros_messages.hpp"
#include "daemon/dds/ros_time.hpp"
#include "daemon/dds/topics.hpp"
#include "daemon/feeders/sim_run.hpp"
#include "daemon/stack/settings.hpp"
#include "nav_msgs/msg/OdometryPubSubTypes.h"
#include "sensor_msgs/msg/PointCloud2PubSubTypes.h"

namespace {

using namespace fsd;
namespace fdd = fsd::dds;
namespace fdds = eprosima::fastdds::dds;
using Steady = std::chrono::steady_clock;

double percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<std::size_t>(q * (v.size() - 1) + 0.5))];
}

// Counts a topic's samples (and the bytes of clouds), taking each as Fast DDS delivers it.
template <class Msg>
struct Counter final : fdds::DataReaderListener {
  std::atomic<std::uint64_t> n{0}, bytes{0};
  std::vector<double> latency_ms;  // clouds: Unix time now minus the header's stamp (set at write)
  bool latency = false;
  void on_data_available(fdds::DataReader* r) override {
    Msg m;
    fdds::SampleInfo info;
    while (r->take_next_sample(&m, &info) == ReturnCode_t::RETCODE_OK) {
      if (!info.valid_data) continue;
      ++n;
      if constexpr (std::is_same_v<Msg, sensor_msgs::msg::dds_::PointCloud2_>) {
        bytes += m.data().size();
        if (latency)
          latency_ms.push_back(
              1e3 * (fdd::run_epoch(0) - fdd::from_ros_time({m.header().stamp().sec(), m.header().stamp().nanosec()})));
      }
    }
  }
};

fdd::DdsSettings bench_dds() {
  fdd::DdsSettings s;
  s.enabled = true;
  s.domain = 77;
  s.initial_peers = "127.0.0.1";
  return s;
}

struct LoopFigures {
  double p50, p99, max;
  std::size_t cycles;
};

LoopFigures control_loop(bool with_dds, double seconds) {
  Config cfg(config_schema());
  cfg.set("sim.enable_camera", false, "bench");
  cfg.set("run.track", std::string("../shared/tracks/epfl_track_1.csv"), "bench");
  if (with_dds) {
    cfg.set("dds.enabled", true, "bench");
    cfg.set("dds.domain", 77, "bench");
    cfg.set("dds.initial_peers", std::string("127.0.0.1"), "bench");
  }
  RunOptions o;
  o.sim = true;
  SimRun run(cfg, o);
  std::vector<double> periods;
  periods.reserve(static_cast<std::size_t>(seconds * 110));
  Steady::time_point last{};
  run.set_loop_hook([&] {
    const auto now = Steady::now();
    if (last != Steady::time_point{}) periods.push_back(std::chrono::duration<double, std::milli>(now - last).count());
    last = now;
  });
  std::atomic<bool> stop{false};
  std::thread timer([&] {
    std::this_thread::sleep_for(std::chrono::duration<double>(seconds));
    stop = true;
  });
  run.run(stop);
  timer.join();
  return {percentile(periods, 0.5), percentile(periods, 0.99), percentile(periods, 1.0), periods.size()};
}

}  // namespace

int main(int argc, char** argv) {
  const double seconds = argc > 1 ? std::atof(argv[1]) : 20.0;
  init_logging("warn");
  // Two participants of one process would hand samples over in memory; off, they go through the transports, as
  // between two processes on one computer (Fast DDS's shared memory; UDP on loopback for another middleware).
  eprosima::fastrtps::LibrarySettingsAttributes lib;
  lib.intraprocess_delivery = eprosima::fastrtps::INTRAPROCESS_OFF;
  eprosima::fastrtps::xmlparser::XMLProfileManager::library_settings(lib);

  // A reader of the loud topics in a participant of its own, so that the bridge's writes are real.
  fdd::Participant reader(bench_dds(), "bench-reader");
  Counter<sensor_msgs::msg::dds_::PointCloud2_> clouds;
  Counter<nav_msgs::msg::dds_::Odometry_> odoms;
  reader.reader(fdd::kCloudTopic, fdds::TypeSupport(new sensor_msgs::msg::dds_::PointCloud2_PubSubType),
                fdd::TopicKind::Stream, &clouds);
  reader.reader(fdd::kOdomTopic, fdds::TypeSupport(new nav_msgs::msg::dds_::Odometry_PubSubType), fdd::TopicKind::State,
                &odoms);

  // Off and on in turn, three times each (the machine's load drifts; the first run also warms the caches).
  std::printf("control loop period, %.0f s of fsd run --sim in real time per run (ms):\n", seconds);
  std::vector<double> p99_off, p99_on;
  for (int rep = 0; rep < 3; ++rep)
    for (const bool with_dds : {false, true}) {
      clouds.n = 0;
      odoms.n = 0;
      const LoopFigures f = control_loop(with_dds, seconds);
      (with_dds ? p99_on : p99_off).push_back(f.p99);
      std::printf("  dds %-3s p50 %.3f  p99 %.3f  max %.3f  (%zu cycles; %llu clouds, %llu odometry read)\n",
                  with_dds ? "on" : "off", f.p50, f.p99, f.max, f.cycles,
                  static_cast<unsigned long long>(clouds.n.load()), static_cast<unsigned long long>(odoms.n.load()));
    }
  std::printf("  median p99: off %.3f, on %.3f, rise %.3f ms\n", percentile(p99_off, 0.5), percentile(p99_on, 0.5),
              percentile(p99_on, 0.5) - percentile(p99_off, 0.5));

  // The cloud alone: a VLP-16 scan's size (28800 points: 16 lasers x 1800 firings), written at 10 Hz, then flat out.
  fdd::Participant writer(bench_dds(), "bench-writer");
  auto* w = writer.writer(fdd::kCloudTopic, fdds::TypeSupport(new sensor_msgs::msg::dds_::PointCloud2_PubSubType),
                          fdd::TopicKind::Stream);
  std::this_thread::sleep_for(std::chrono::seconds(2));  // discovery
  Scan scan;
  scan.points.resize(28800);
  for (std::size_t k = 0; k < scan.points.size(); ++k)
    scan.points[k] = Point{float(k % 100), 1, 0, 10, std::uint16_t(k % 16), 0, 5, 0};
  clouds.n = 0;
  clouds.bytes = 0;
  clouds.latency = true;
  const int paced = 100;
  for (int k = 0; k < paced; ++k) {
    scan.stamp = 0;
    auto m = fdd::to_point_cloud(scan, fdd::run_epoch(0));  // stamped now (epoch + 0)
    w->write(&m);
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  const auto lat = clouds.latency_ms;
  const auto bytes_per_cloud = scan.points.size() * 24;
  std::printf("cloud at 10 Hz (%zu B each): %llu of %d arrived; write to callback p50 %.2f ms, p99 %.2f ms\n",
              bytes_per_cloud, static_cast<unsigned long long>(clouds.n.load()), paced, percentile(lat, 0.5),
              percentile(lat, 0.99));
  clouds.latency = false;
  clouds.n = 0;
  clouds.bytes = 0;
  int sent = 0;
  const auto t0 = Steady::now();
  auto m = fdd::to_point_cloud(scan, fdd::run_epoch(0));
  while (Steady::now() - t0 < std::chrono::seconds(2)) {
    w->write(&m);
    ++sent;
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  const double s = std::chrono::duration<double>(Steady::now() - t0).count() - 0.5;
  std::printf("cloud flat out for 2 s: %d written, %llu arrived (%.0f /s, %.1f MB/s)\n", sent,
              static_cast<unsigned long long>(clouds.n.load()), clouds.n.load() / s, clouds.bytes.load() / s / 1e6);
  return 0;
}
