// fsd-web-demo: the dashboard server with synthetic telemetry, for the browser test and for working on the
// dashboard without the stack. A car drives the centre line of a track file at the tunable speed
// demo.target_speed; cones are "mapped" as the car passes them; detections, a point cloud, paths, AS state,
// laps, a fault and log lines are made up from the track's truth. Not the autonomy stack: `fsd run --sim` is.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <csignal>
#include <iostream>
#include <numbers>
#include <random>
#include <thread>

#include <CLI/CLI.hpp>

#include "common/clock.hpp"
#include "common/config.hpp"
#include "common/logging.hpp"
#include "common/params.hpp"
#include "common/track.hpp"
#include "web/channels.hpp"
#include "web/config.hpp"
#include "web/log_sink.hpp"
#include "web/server.hpp"

namespace {

using namespace fsd;
using namespace fsd::web;

std::atomic<bool> g_stop{false};

struct DemoTuning {
  double target_speed = 6.0;  // m/s
  double lookahead = 20.0;    // m of planned path shown
};

const ConfigSection<DemoTuning>& demo_section() {
  static const auto s = ConfigSection<DemoTuning>("demo")
                            .number("target_speed", &DemoTuning::target_speed, 0.0, 20.0, "m/s",
                                    "Speed of the synthetic car", true)
                            .number("lookahead", &DemoTuning::lookahead, 2.0, 60.0, "m",
                                    "Length of the planned path shown", true);
  return s;
}

// The centre line: midpoints of each left cone and its nearest right cone, ordered by walking to the nearest
// unvisited midpoint from the start, closed, resampled every `step` metres.
std::vector<Vec2> centre_line(const Track& t, double step) {
  std::vector<Vec2> left, right, mids;
  for (const auto& c : t.cones) (c.role == ConeRole::Left ? left : c.role == ConeRole::Right ? right : mids).push_back(c.position);
  mids.clear();
  for (const auto& l : left) {
    const auto it = std::min_element(right.begin(), right.end(), [&](const Vec2& a, const Vec2& b) { return (a - l).norm() < (b - l).norm(); });
    if (it != right.end()) mids.push_back((l + *it) / 2);
  }
  std::vector<Vec2> ordered;
  Vec2 at = t.start.position();
  // Start ahead of the car: skip midpoints behind it.
  const Vec2 fwd(std::cos(t.start.yaw), std::sin(t.start.yaw));
  while (!mids.empty()) {
    auto best = mids.begin();
    double best_d = 1e18;
    for (auto it = mids.begin(); it != mids.end(); ++it) {
      double d = (*it - at).norm();
      if (ordered.empty() && (*it - at).dot(fwd) < 0) d += 1e6;
      if (d < best_d) best_d = d, best = it;
    }
    at = *best;
    ordered.push_back(at);
    mids.erase(best);
  }
  if (ordered.size() < 3) throw std::runtime_error("track has too few left/right cones for a centre line");
  // Smooth the zig-zag of nearest-cone midpoints (a moving average over the closed loop).
  std::vector<Vec2> smooth(ordered.size(), Vec2::Zero());
  const int n = static_cast<int>(ordered.size()), k = 2;
  for (int i = 0; i < n; ++i) {
    for (int j = -k; j <= k; ++j) smooth[i] += ordered[((i + j) % n + n) % n];
    smooth[i] /= 2 * k + 1;
  }
  ordered = std::move(smooth);
  ordered.push_back(ordered.front());
  std::vector<Vec2> out{ordered.front()};
  double carry = 0;
  for (std::size_t i = 1; i < ordered.size(); ++i) {
    const Vec2 a = ordered[i - 1], b = ordered[i];
    const double len = (b - a).norm();
    double s = step - carry;
    for (; s <= len; s += step) out.push_back(a + (b - a) * (s / len));
    carry = len - (s - step);
  }
  return out;
}

struct PathFollower {
  std::vector<Vec2> line;
  std::vector<double> s;  // arc length at each point
  double length = 0;
  explicit PathFollower(std::vector<Vec2> l) : line(std::move(l)) {
    s.push_back(0);
    for (std::size_t i = 1; i < line.size(); ++i) s.push_back(s.back() + (line[i] - line[i - 1]).norm());
    length = s.back();
  }
  Vec2 at(double d) const {
    d = std::fmod(std::fmod(d, length) + length, length);
    const auto i = static_cast<std::size_t>(std::upper_bound(s.begin(), s.end(), d) - s.begin());
    const std::size_t j = std::clamp<std::size_t>(i, 1, line.size() - 1);
    const double f = (d - s[j - 1]) / std::max(1e-9, s[j] - s[j - 1]);
    return line[j - 1] + (line[j] - line[j - 1]) * f;
  }
  double heading(double d) const {
    const Vec2 a = at(d - 0.5), b = at(d + 0.5);
    return std::atan2(b.y() - a.y(), b.x() - a.x());
  }
  double curvature(double d) const { return wrap_angle(heading(d + 1.5) - heading(d - 1.5)) / 3.0; }
};

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"fsd-web-demo: the dashboard with synthetic telemetry (a car driving a track's centre line)"};
  std::string track_file = "../shared/tracks/epfl_track_1.csv";
  int port = 8080;
  std::string bind = "127.0.0.1";
  std::string token;
  double duration = 0;
  app.add_option("--track", track_file, "Track CSV");
  app.add_option("--port", port, "Port (0 = any free port, printed on stdout)");
  app.add_option("--bind", bind, "Bind address");
  app.add_option("--token", token, "Tuning token (FSD_WEB_TOKEN overrides)");
  app.add_option("--duration", duration, "Stop after this many seconds (0 = until SIGINT/SIGTERM)");
  CLI11_PARSE(app, argc, argv);

  init_logging("info");
  std::signal(SIGINT, [](int) { g_stop = true; });
  std::signal(SIGTERM, [](int) { g_stop = true; });

  Track track;
  try {
    track = load_track(track_file);
  } catch (const std::exception& e) {
    std::cerr << "fsd-web-demo: " << e.what() << "\n";
    return 2;
  }
  auto schema = std::make_shared<ConfigSchema>();
  web_section().describe(*schema);
  demo_section().describe(*schema);
  Config config(schema);
  config.set("web.port", port, "command line");
  config.set("web.bind", bind, "command line");
  config.set("web.token", token, "command line");
  config.set("web.web_root", "web/dashboard/dist", "default");
  RealClock clock;
  ParamRegistry params(config, &clock);
  const auto speed_param = params.handle("demo.target_speed");
  const auto lookahead_param = params.handle("demo.lookahead");

  WebServer server(web_section().read(config), params, clock);
  const auto ch = add_standard_channels(server);
  const auto log_sink = make_log_sink(server, ch.log, clock);
  auto log = logger("demo");
  log->sinks().push_back(log_sink);
  try {
    server.start();
  } catch (const std::exception& e) {
    std::cerr << "fsd-web-demo: " << e.what() << "\n";
    return 2;
  }
  std::cout << "fsd-web-demo listening on http://" << bind << ":" << server.port() << "/" << std::endl;

  const PathFollower path(centre_line(track, 0.5));
  auto& step_latency = server.metrics().summary("fsd_stage_latency_seconds", "Latency of each stage", {{"stage", "demo_step"}});
  auto& as_gauge = server.metrics().gauge("fsd_as_state", "AS state: 0 Off, 1 Ready, 2 Driving, 3 Emergency, 4 Finished");

  std::mt19937 rng(1);
  std::normal_distribution<double> noise(0.0, 1.0);
  std::vector<bool> mapped(track.cones.size(), false);
  PathSet paths;
  AsStatusView as;
  as.mission = Mission::Trackdrive;
  as.laps_total = 0;
  std::vector<FaultEvent> faults;
  double s = 0, v = 0, lap_start = 0;
  std::uint64_t tick = 0;
  const double dt = 0.01;
  const Stamp t0 = clock.now();

  server.set_state_provider([&server] { return nlohmann::json{{"demo", true}, {"clients", server.client_count()}}; });

  while (!g_stop && (duration <= 0 || clock.now() - t0 < duration)) {
    const Stamp t = t0 + static_cast<double>(tick) * dt;
    if (!clock.sleep_until(t)) break;
    const auto work_start = std::chrono::steady_clock::now();
    const double run_t = t - t0;
    ++tick;

    // AS state: Off, Ready, then driving for good.
    const AsState state = run_t < 1.0 ? AsState::Off : run_t < 3.0 ? AsState::Ready : AsState::Driving;
    if (state != as.as_state) log->info("AS state {}", to_string(state));
    as.as_state = state;
    as_gauge.set(static_cast<double>(state));
    const double target = state == AsState::Driving ? speed_param.get() : 0.0;
    v += (target - v) * std::min(1.0, dt / 0.8);
    const double prev_s = s;
    s += v * dt;
    if (std::floor(s / path.length) > std::floor(prev_s / path.length)) {
      as.lap_times.push_back(run_t - lap_start);
      lap_start = run_t;
      ++as.lap;
      log->info("lap {} in {:.2f} s", as.lap, as.lap_times.back());
    }
    as.lap_time = state == AsState::Driving ? run_t - lap_start : 0.0;
    if (state != AsState::Driving) lap_start = run_t;
    as.control_mode = as.lap == 0 ? "lap 1: midline of the cone map" : "lap 2+: stored lap-1 trajectory";

    const Vec2 p = path.at(s);
    const double kappa = path.curvature(s);
    VehicleState vs;
    vs.stamp = t;
    vs.pose = {p.x(), p.y(), path.heading(s)};
    vs.vx = v;
    vs.yaw_rate = v * kappa + 0.01 * noise(rng);
    vs.ay = v * v * kappa + 0.05 * noise(rng);
    vs.vy = -0.015 * vs.ay * std::max(v, 0.0) / 9.81 * 4.0;  // a small slip that follows the lateral load
    vs.ax = (target - v) / 0.8;
    vs.steering = std::atan(1.53 * kappa);
    server.publish(ch.vehicle_state, t, vehicle_state_json(vs, target));

    if (tick % 5 == 0) server.publish(ch.car, t, car_scene(t, vs.pose));

    if (tick % 10 == 0) {
      // Detections within 15 m ahead; they also put cones on the map.
      ConeDetections det;
      std::vector<Point> ground, objects;
      for (std::size_t i = 0; i < track.cones.size(); ++i) {
        const auto& c = track.cones[i];
        const Vec2 local = vs.pose.inverse_transform(c.position);
        if (local.norm() > 20.0 || local.x() < -2.0) continue;
        mapped[i] = true;
        if (local.x() > 0.5 && local.norm() < 15.0) {
          Cone k;
          k.position = Vec3(local.x() + 0.03 * noise(rng), local.y() + 0.03 * noise(rng), 0);
          k.colour = c.colour;
          det.cones.push_back(k);
        }
        for (int j = 0; j < 24; ++j) {  // points on the cone's surface
          const double h = 0.3 * (j % 6) / 6.0, a = 2 * std::numbers::pi * (j / 6) / 4.0 + std::atan2(-local.y(), -local.x());
          const double r = 0.11 * (1 - h / 0.33);
          objects.push_back({static_cast<float>(local.x() + r * std::cos(a)), static_cast<float>(local.y() + r * std::sin(a)),
                             static_cast<float>(h), 60.0f});
        }
      }
      for (double gx = -6; gx <= 20; gx += 0.8)
        for (double gy = -10; gy <= 10; gy += 0.8)
          ground.push_back({static_cast<float>(gx), static_cast<float>(gy), static_cast<float>(0.01 * noise(rng)), 10.0f});
      server.publish(ch.detections, t, detections_scene(t, det, vs.pose));
      server.publish(ch.point_cloud, t, point_cloud(t, vs.pose.to_pose3(), ground, objects));
    }

    if (tick % 100 == 0) {
      std::vector<Cone> map;
      for (std::size_t i = 0; i < track.cones.size(); ++i) {
        if (!mapped[i]) continue;
        Cone c;
        c.position = Vec3(track.cones[i].position.x(), track.cones[i].position.y(), 0);
        c.colour = track.cones[i].colour;
        c.id = static_cast<std::uint32_t>(i + 1);
        map.push_back(c);
      }
      server.publish(ch.cone_map, t, cone_map_scene(t, map));
    }

    if (tick % 50 == 0) {
      auto& driven = as.lap == 0 ? paths.lap1_trajectory : paths.lap2_tracking;
      if (state == AsState::Driving && as.lap <= 1) driven.push_back(p);
      paths.planned.clear();
      for (double d = 0; d <= lookahead_param.get(); d += 1.0) paths.planned.push_back(path.at(s + d));
      server.publish(ch.paths, t, paths_scene(t, paths));
      server.publish(ch.as_status, t, as_status_json(t, as));
    }

    // A fault that comes and goes, to see the panel work.
    if (tick == 2000) {
      faults.push_back({run_t, "gnss", "fix quality dropped to single", "fallback to real-time planning", true});
      log->warn("gnss: fix quality dropped to single");
    }
    if (tick == 2500 && !faults.empty()) faults.back().active = false;
    if (tick % 200 == 0 || tick == 2000 || tick == 2500) server.publish(ch.faults, t, faults_json(t, faults));

    step_latency.observe(std::chrono::duration<double>(std::chrono::steady_clock::now() - work_start).count());
  }
  log->sinks().pop_back();
  server.stop();
  return 0;
}
