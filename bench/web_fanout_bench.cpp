// The web server under load: a simulated 100 Hz control loop publishes the dashboard's telemetry at the
// daemon's rates while 0 or 20 WebSocket clients on loopback subscribe to everything. Reports the loop's period
// jitter (the control thread must not notice the clients), the cost of publish() and the telemetry latency from
// publish() to a client's read. Run: build/bench/web_fanout_bench [seconds per case, default 10]
#include <pthread.h>
#include <sched.h>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <utility>  // before Asio (Boost 1.74)
#include <vector>

#include <spdlog/spdlog.h>
#include <boost/asio.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/websocket.hpp>
#include <nlohmann/json.hpp>

#include "common/clock.hpp"
#include "common/config.hpp"
#include "common/params.hpp"
#include "daemon/telemetry/telemetry_channels.hpp"
#include "web/channels.hpp"
#include "web/config.hpp"
#include "web/server.hpp"

namespace {

namespace net = boost::asio;
namespace beast = boost::beast;
namespace websocket = beast::websocket;
using tcp = net::ip::tcp;
using Clock = std::chrono::steady_clock;
using namespace fsd;

std::int64_t now_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now().time_since_epoch()).count();
}

struct Stats {
  std::vector<double> v;
  double pct(double q) {
    if (v.empty()) return 0;
    std::sort(v.begin(), v.end());
    return v[std::min(v.size() - 1, static_cast<std::size_t>(q * static_cast<double>(v.size())))];
  }
};

// A client that subscribes to every advertised channel and measures the latency of /vehicle/state messages.
class BenchClient : public std::enable_shared_from_this<BenchClient> {
 public:
  BenchClient(net::io_context& ioc, std::mutex& m, std::vector<double>& latencies)
      : ws_(net::make_strand(ioc)), m_(m), latencies_(latencies) {}
  bool connect(std::uint16_t port) {
    beast::error_code ec;
    beast::get_lowest_layer(ws_).connect(tcp::endpoint(net::ip::make_address("127.0.0.1"), port), ec);
    if (ec) return false;
    ws_.set_option(websocket::stream_base::decorator([](websocket::request_type& r) {
      r.set(beast::http::field::sec_websocket_protocol, "foxglove.websocket.v1");
    }));
    ws_.read_message_max(16 * 1024 * 1024);
    ws_.handshake("127.0.0.1", "/", ec);
    return !ec;
  }
  void start() { read(); }
  void close() {
    net::post(ws_.get_executor(), [self = shared_from_this()] {
      beast::error_code ec;
      beast::get_lowest_layer(self->ws_).socket().close(ec);
    });
  }
  std::atomic<std::uint64_t> messages{0}, bytes{0};

 private:
  void read() {
    ws_.async_read(buf_, [self = shared_from_this()](beast::error_code ec, std::size_t n) {
      if (ec) return;
      self->on_message(n);
      self->buf_.consume(self->buf_.size());
      self->read();
    });
  }
  void on_message(std::size_t n) {
    const auto data = buf_.cdata();
    const char* p = static_cast<const char*>(data.data());
    if (!ws_.got_binary()) {
      const auto j = nlohmann::json::parse(p, p + data.size(), nullptr, false);
      if (j.is_object() && j.value("op", "") == "advertise") {
        nlohmann::json subs = nlohmann::json::array();
        for (const auto& c : j["channels"]) subs.push_back({{"id", c["id"]}, {"channelId", c["id"]}});
        auto text = std::make_shared<std::string>(nlohmann::json{{"op", "subscribe"}, {"subscriptions", subs}}.dump());
        // Writes from the read handler: one at a time is guaranteed here (advertise comes once).
        ws_.text(true);
        ws_.async_write(net::buffer(*text), [text](beast::error_code, std::size_t) {});
      }
      return;
    }
    if (data.size() < 13 || p[0] != 0x01) return;
    messages.fetch_add(1, std::memory_order_relaxed);
    bytes.fetch_add(n, std::memory_order_relaxed);
    const std::string_view payload(p + 13, data.size() - 13);
    if (payload.rfind("{\"sent_ns\":", 0) == 0) {
      const auto sent = std::stoll(std::string(payload.substr(11, 20)));
      std::lock_guard lock(m_);
      latencies_.push_back(static_cast<double>(now_ns() - sent) * 1e-6);
    }
  }

  websocket::stream<beast::tcp_stream> ws_;
  beast::flat_buffer buf_;
  std::mutex& m_;
  std::vector<double>& latencies_;
};

struct Result {
  int clients;
  double jitter_p50, jitter_p99, jitter_max;     // ms, |period - 10 ms|
  double publish_p50, publish_p99, publish_max;  // µs per publish() call
  double latency_p50, latency_p99, latency_max;  // ms, vehicle state publish → client read
  double received_fraction;                      // of vehicle-state messages, over all clients
  double mbytes_per_s;                           // to all clients
  std::uint64_t dropped;
};

// The daemon runs its control thread with real-time priority on the car; do the same here when allowed.
bool make_realtime() {
  sched_param p{};
  p.sched_priority = 50;
  return pthread_setschedparam(pthread_self(), SCHED_FIFO, &p) == 0;
}

Result run_case(int n_clients, double seconds, bool realtime) {
  struct Tuning {
    double x = 1;
  };
  static const auto section = ConfigSection<Tuning>("bench").number("x", &Tuning::x, 0, 10, "", "unused", true);
  auto schema = std::make_shared<ConfigSchema>();
  section.describe(*schema);
  web::web_section().describe(*schema);
  Config config(schema);
  RealClock clock;
  ParamRegistry params(config, &clock);
  auto wcfg = web::web_section().read(config);
  wcfg.bind = "127.0.0.1";
  wcfg.port = 0;
  wcfg.max_clients = 32;
  wcfg.web_root = "/nonexistent";
  web::WebServer server(wcfg, params, clock);
  const auto ids = web::add_channels(server, channel_specs([](const TelemetryChannel& c) { return !c.truth; }));
  server.start();

  net::io_context client_ioc;
  std::mutex m;
  std::vector<double> latencies;
  std::vector<std::shared_ptr<BenchClient>> clients;
  for (int i = 0; i < n_clients; ++i) {
    auto c = std::make_shared<BenchClient>(client_ioc, m, latencies);
    if (!c->connect(server.port())) throw std::runtime_error("bench client cannot connect");
    c->start();
    clients.push_back(c);
  }
  auto work = net::make_work_guard(client_ioc);
  std::thread client_thread([&] { client_ioc.run(); });
  std::this_thread::sleep_for(std::chrono::milliseconds(300));  // subscriptions in place

  // Synthetic payloads of realistic size.
  std::vector<Cone> cones(200);
  for (std::size_t i = 0; i < cones.size(); ++i) cones[i].position = Vec3(0.5 * i, (i % 2) ? 2.0 : -2.0, 0);
  std::vector<Point> ground(6000), objects(2000);
  for (std::size_t i = 0; i < ground.size(); ++i)
    ground[i] = {float(i % 80) * 0.25f, float(i / 80) * 0.25f, 0.0f, 10.0f};
  for (std::size_t i = 0; i < objects.size(); ++i)
    objects[i] = {float(i % 40) * 0.3f, float(i / 40) * 0.2f, 0.2f, 60.0f};
  web::PathSet paths;
  for (int i = 0; i < 600; ++i) paths.lap1_trajectory.emplace_back(0.5 * i, std::sin(0.01 * i));

  Stats jitter, publish_cost;
  const int ticks = static_cast<int>(seconds * 100);
  // The simulated control thread: wakes every 10 ms, builds and publishes that tick's telemetry.
  std::thread loop([&] {
    if (realtime) make_realtime();
    const auto period = std::chrono::milliseconds(10);
    auto next = Clock::now() + period;
    auto last_wake = Clock::now();
    VehicleState vs;
    const auto timed_publish = [&](web::ChannelId c, Stamp t, std::string payload) {
      const auto a = Clock::now();
      server.publish(c, t, std::move(payload));
      publish_cost.v.push_back(std::chrono::duration<double, std::micro>(Clock::now() - a).count());
    };
    for (int tick = 0; tick < ticks; ++tick) {
      std::this_thread::sleep_until(next);
      const auto woke = Clock::now();
      if (tick > 0)
        jitter.v.push_back(std::abs(std::chrono::duration<double, std::milli>(woke - last_wake).count() - 10.0));
      last_wake = woke;
      next += period;
      const Stamp t = tick * 0.01;
      vs.stamp = t;
      vs.vx = 8.0;
      vs.pose = {0.08 * tick, 0, 0};
      // The payload starts with the send time so clients can measure latency.
      const std::string state = web::vehicle_state_json(vs, 8.0);
      timed_publish(ids.at(web::topics::kVehicleState), t,
                    "{\"sent_ns\":" + std::to_string(now_ns()) + "," + state.substr(1));
      if (tick % 5 == 0) timed_publish(ids.at(web::topics::kCar), t, web::car_scene(t, vs.pose));
      if (tick % 10 == 0) {
        ConeDetections d;
        d.cones.assign(cones.begin(), cones.begin() + 12);
        timed_publish(ids.at(web::topics::kDetections), t, web::detections_scene(t, d, vs.pose));
      }
      if (tick % 20 == 0)
        timed_publish(ids.at(web::topics::kPointCloud), t, web::point_cloud(t, vs.pose.to_pose3(), ground, objects));
      if (tick % 50 == 0) {
        timed_publish(ids.at(web::topics::kPaths), t, web::paths_scene(t, paths));
        timed_publish(ids.at(web::topics::kAsStatus), t, web::as_status_json(t, {}));
      }
      if (tick % 100 == 0) timed_publish(ids.at(web::topics::kConeMap), t, web::cone_map_scene(t, cones));
    }
  });
  loop.join();
  std::this_thread::sleep_for(std::chrono::milliseconds(300));  // let the last messages arrive

  Result r{};
  r.clients = n_clients;
  r.jitter_p50 = jitter.pct(0.5);
  r.jitter_p99 = jitter.pct(0.99);
  r.jitter_max = jitter.pct(1.0);
  r.publish_p50 = publish_cost.pct(0.5);
  r.publish_p99 = publish_cost.pct(0.99);
  r.publish_max = publish_cost.pct(1.0);
  std::uint64_t bytes = 0;
  {
    std::lock_guard lock(m);
    Stats lat{latencies};
    r.latency_p50 = lat.pct(0.5);
    r.latency_p99 = lat.pct(0.99);
    r.latency_max = lat.pct(1.0);
    r.received_fraction =
        n_clients ? static_cast<double>(latencies.size()) / (static_cast<double>(ticks) * n_clients) : 0;
  }
  for (const auto& c : clients) bytes += c->bytes.load();
  r.mbytes_per_s = static_cast<double>(bytes) / seconds / 1e6;
  const auto metrics = server.metrics().render();
  const auto pos = metrics.find("\nfsd_web_messages_dropped_total ");
  r.dropped = pos == std::string::npos ? 0 : std::stoull(metrics.substr(pos + 32));
  for (auto& c : clients) c->close();
  work.reset();
  client_thread.join();
  server.stop();
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  const double seconds = argc > 1 ? std::atof(argv[1]) : 10.0;
  spdlog::set_level(spdlog::level::warn);
  bool realtime = false;
  std::thread([&] { realtime = make_realtime(); }).join();
  std::printf(
      "web fan-out: 100 Hz loop publishing vehicle state 100 Hz, car 20 Hz, detections 10 Hz, cloud 5 Hz "
      "(8000 → 5000 points), paths + AS 2 Hz, cone map 1 Hz; %.0f s per case; loop thread %s\n\n",
      seconds, realtime ? "SCHED_FIFO 50 (as on the car)" : "normal priority (SCHED_FIFO not permitted)");
  std::printf(
      "| clients | loop jitter p50 / p99 / max (ms) | publish() p50 / p99 / max (µs) | latency p50 / p99 / max (ms) | "
      "state msgs received | MB/s out | dropped |\n");
  std::printf("|---|---|---|---|---|---|---|\n");
  for (const int n : {0, 20}) {
    const auto r = run_case(n, seconds, realtime);
    std::printf("| %d | %.3f / %.3f / %.3f | %.1f / %.1f / %.1f | %.2f / %.2f / %.2f | %.1f %% | %.1f | %llu |\n",
                r.clients, r.jitter_p50, r.jitter_p99, r.jitter_max, r.publish_p50, r.publish_p99, r.publish_max,
                r.latency_p50, r.latency_p99, r.latency_max, 100.0 * r.received_fraction, r.mbytes_per_s,
                static_cast<unsigned long long>(r.dropped));
    std::fflush(stdout);
  }
  return 0;
}
