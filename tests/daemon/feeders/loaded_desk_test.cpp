// `fsd run --sim` in real time on a busy desk (issue #18): every core kept busy by a CPU hog that ends by itself,
// and a dashboard subscribed to every channel reading all it is sent. The run must still finish its lap with no
// cone hit and without Emergency: a plan that waited for a core is not a late plan, and no watchdog may mistake
// a starved thread for a failed stage. Truth is the virtual car's scorecard and the exit status of
// --until-finished.
#include <gtest/gtest.h>

#include <time.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/thread_cpu.hpp"
#include "tests/daemon/telemetry/dashboard_client.hpp"
#include "tests/daemon/fsd_child.hpp"
#include "tests/scratch_dir.hpp"

namespace fsd {
namespace {

using namespace std::chrono_literals;
using Clock = std::chrono::steady_clock;

// One busy-looping thread per core, at the daemon's own priority, until stopped or `limit` has passed (so that
// it ends even if the test does not); reports the CPU time the hog got.
class CpuHog {
 public:
  explicit CpuHog(std::chrono::seconds limit) {
    const unsigned n = std::max(2u, std::thread::hardware_concurrency());
    const auto until = Clock::now() + limit;
    cpu_.assign(n, 0.0);
    for (unsigned i = 0; i < n; ++i)
      threads_.emplace_back([this, i, until] {
        const double c0 = thread_cpu_seconds();
        volatile std::uint64_t spin = 0;
        while (!stop_.load(std::memory_order_relaxed) && Clock::now() < until)
          for (int k = 0; k < 10000; ++k) spin = spin + 1;
        cpu_[i] = thread_cpu_seconds() - c0;
      });
  }
  ~CpuHog() { stop(); }
  double stop() {
    stop_ = true;
    for (auto& t : threads_)
      if (t.joinable()) t.join();
    double total = 0;
    for (const double c : cpu_) total += c;
    return total;
  }

 private:
  std::atomic<bool> stop_{false};
  std::vector<double> cpu_;
  std::vector<std::thread> threads_;
};

// A dashboard on its own thread: subscribes to every advertised channel and reads everything, counting the
// messages per topic.
class ReadingDashboard {
 public:
  explicit ReadingDashboard(std::uint16_t port) : client_(port) {
    if (!client_.handshake_ok()) return;
    const auto adv = client_.next_op("advertise");
    if (!adv) return;
    nlohmann::json list = nlohmann::json::array();
    std::uint32_t id = 0;
    for (const auto& ch : (*adv)["channels"]) {
      list.push_back({{"id", ++id}, {"channelId", ch["id"]}});
      topics_[id] = ch["topic"].get<std::string>();
    }
    client_.send_text(nlohmann::json{{"op", "subscribe"}, {"subscriptions", list}}.dump());
    reader_ = std::thread([this] {
      while (!stop_) {
        const auto m = client_.next_binary(200ms);
        if (!m || m->size() <= 13 || static_cast<std::uint8_t>((*m)[0]) != 0x01) continue;
        const auto it = topics_.find(test::u32_le(*m, 1));
        if (it != topics_.end()) ++counts_[it->second];
      }
    });
  }
  ~ReadingDashboard() { stop(); }
  std::size_t channels() const { return topics_.size(); }
  std::map<std::string, int> stop() {
    stop_ = true;
    if (reader_.joinable()) reader_.join();
    return counts_;
  }

 private:
  test::WsClient client_;
  std::map<std::uint32_t, std::string> topics_;
  std::map<std::string, int> counts_;  // written by reader_ only, read after it is joined
  std::atomic<bool> stop_{false};
  std::thread reader_;
};

TEST(LoadedDesk, ARealTimeRunFinishesItsLapWithEveryCoreBusyAndTheDashboardOpen) {
  const std::string report = test::scratch_path("loaded_desk_report.json");
  std::remove(report.c_str());
  // epfl_track_1, one lap: about 40 s of real time with Ready and the stop.
  test::Fsd run({"run", "--sim", "--track", "../shared/tracks/epfl_track_1.csv", "--laps", "1", "--port", "0",
                 "--until-finished", "--report", report},
                test::scratch_path("loaded_desk.log"));
  const auto t0 = Clock::now();
  CpuHog hog(150s);
  const std::string port = run.wait_for(std::regex("dashboard at http://[^/]*:(\\d+)/"), 20s);
  ASSERT_FALSE(port.empty()) << run.output();
  ReadingDashboard dashboard(static_cast<std::uint16_t>(std::stoi(port)));
  ASSERT_GT(dashboard.channels(), 5u) << "no advertise from the dashboard server";

  const int rc = run.wait(140s);
  const double wall = std::chrono::duration<double>(Clock::now() - t0).count();
  const double hog_cpu = hog.stop();
  const auto received = dashboard.stop();
  ASSERT_EQ(rc, 0) << run.output();

  std::ifstream f(report);
  std::stringstream s;
  s << f.rdbuf();
  const auto r = nlohmann::json::parse(s.str());
  EXPECT_EQ(r["as_state"], "Finished") << run.output();
  EXPECT_TRUE(r["finished"].get<bool>());
  EXPECT_EQ(r["laps"].size(), 1u);
  EXPECT_EQ(r["cones_hit"], 0);
  // The load was real: the hog had at least half a core over the run (it competes with the daemon and with
  // whatever else runs on the machine), and the dashboard was sent the car's state throughout (20 Hz nominal).
  EXPECT_GT(hog_cpu, 0.5 * wall) << "hog " << hog_cpu << " s CPU in " << wall << " s";
  EXPECT_GT(received.count("/vehicle/state") ? received.at("/vehicle/state") : 0, static_cast<int>(5 * wall));
  RecordProperty("hog_cpu_s", std::to_string(hog_cpu));
  RecordProperty("wall_s", std::to_string(wall));
}

}  // namespace
}  // namespace fsd
