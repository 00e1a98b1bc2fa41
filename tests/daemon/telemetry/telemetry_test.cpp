// The daemon's side of the dashboard, end to end over real sockets: a headless (lockstep) SimRun on
// epfl_track_1 publishes through Telemetry to a WebServer on 127.0.0.1, and a real WebSocket / HTTP client reads
// what a dashboard or Prometheus would. Expectations come from the shared track file (read here with its own
// parser), the Formula Student rules (5 s in Ready before go) and the loop's fixed rates.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <sstream>
#include <thread>

#include "common/clock.hpp"
#include "common/logging.hpp"
#include "common/params.hpp"
#include "daemon/feeders/sim_run.hpp"
#include "daemon/stack/settings.hpp"
#include "daemon/stack/stack.hpp"
#include "daemon/telemetry/run_metrics.hpp"
#include "daemon/telemetry/telemetry.hpp"
#include "tests/daemon/telemetry/dashboard_client.hpp"
#include "tests/daemon/track_csv.hpp"
#include "tests/web/test_client.hpp"
#include "web/config.hpp"
#include "web/server.hpp"

namespace fsd {
namespace {

using nlohmann::json;
using test::first_on_each;
using test::next_on;
using test::parse_metrics;
using test::subscribe;
using web::test::WsClient;
namespace http = boost::beast::http;

constexpr const char* kTrack = "../shared/tracks/epfl_track_1.csv";

// A headless sim run of `sim_seconds` with the dashboard server, telemetry (truth channels on) and /metrics.
struct LiveRun {
  explicit LiveRun(double sim_seconds, const std::function<void(Config&)>& tweak = {}) : cfg(config_schema()) {
    cfg.set("sim.enable_lidar", false, "test");
    cfg.set("sim.enable_camera", false, "test");
    cfg.set("run.perception_source", std::string("truth"), "test");
    cfg.set("run.localization_source", std::string("truth"), "test");
    cfg.set("run.track", kTrack, "test");
    if (tweak) tweak(cfg);
    cfg.set("run.max_sim_time", sim_seconds, "test");
    cfg.set("web.bind", "127.0.0.1", "test");
    cfg.set("web.port", 0, "test");
    params = std::make_unique<ParamRegistry>(cfg, &clock);
    server = std::make_unique<web::WebServer>(web::web_section().read(cfg), *params, clock);
    telemetry = std::make_unique<Telemetry>(*server, true);
    metrics = std::make_unique<RunMetrics>(server->metrics());
    server->start();
    RunOptions o;
    o.sim = true;
    o.headless = true;
    run = std::make_unique<SimRun>(cfg, o);
    run->set_telemetry(telemetry.get());
    run->set_metrics(metrics.get());
  }
  ~LiveRun() {
    telemetry->stop();
    server->stop();
  }
  int go() {
    std::atomic<bool> stop{false};
    return run->run(stop);
  }

  Config cfg;
  RealClock clock;
  std::unique_ptr<ParamRegistry> params;
  std::unique_ptr<web::WebServer> server;
  std::unique_ptr<Telemetry> telemetry;
  std::unique_ptr<RunMetrics> metrics;
  std::unique_ptr<SimRun> run;
};

struct FileCone {
  std::string tag;
  double x = 0, y = 0;
};

// The track file's cones, read independently of common/track.
std::vector<FileCone> read_cones(const std::string& path, double* start_x, double* start_y, double* start_yaw) {
  std::vector<FileCone> out;
  for (const auto& r : test::read_track_csv(path)) {
    if (r.tag == "car_start") {
      *start_x = r.x;
      *start_y = r.y;
      *start_yaw = r.direction;
      continue;
    }
    out.push_back({r.tag, r.x, r.y});
  }
  return out;
}

TEST(Telemetry, TruthChannelsCarryTheTrackFilesConesAndTheTrueStartPose) {
  double sx = NAN, sy = NAN, syaw = NAN;
  const auto file = read_cones(kTrack, &sx, &sy, &syaw);
  ASSERT_GT(file.size(), 100u);

  LiveRun live(3.0);  // the car stands in Off/Ready for the first 5 s
  WsClient c(live.server->port());
  ASSERT_TRUE(c.handshake_ok());
  auto subs = subscribe(c, {"/truth/cones", "/truth/vehicle_state", "/truth/car"});
  ASSERT_EQ(subs.size(), 3u);
  ASSERT_EQ(live.go(), 0);

  auto first = first_on_each(c, {subs["/truth/cones"], subs["/truth/vehicle_state"], subs["/truth/car"]});
  const auto pick = [&](const char* topic) -> std::optional<json> {
    const auto it = first.find(subs[topic]);
    return it == first.end() ? std::nullopt : std::optional<json>(it->second);
  };
  const auto cones = pick("/truth/cones");
  ASSERT_TRUE(cones);
  const auto& standing = (*cones)["entities"][0];
  const auto& knocked = (*cones)["entities"][1];
  EXPECT_EQ(standing["id"], "truth_cones");
  EXPECT_EQ(knocked["id"], "truth_knocked_cones");
  EXPECT_EQ(knocked["cylinders"].size(), 0u);
  ASSERT_EQ(standing["cylinders"].size(), file.size());
  bool labelled = false;
  for (const auto& kv : standing["metadata"])
    labelled |= kv["key"] == "source" && kv["value"] == "simulator ground truth";
  EXPECT_TRUE(labelled);
  // Every cone of the file has its own cylinder at its position, of the rules' size, in its colour.
  std::vector<bool> used(file.size(), false);
  for (const auto& fc : file) {
    std::size_t best = file.size();
    double best_d = 1e9;
    for (std::size_t i = 0; i < standing["cylinders"].size(); ++i) {
      const auto& p = standing["cylinders"][i]["pose"]["position"];
      const double d = std::hypot(p["x"].get<double>() - fc.x, p["y"].get<double>() - fc.y);
      if (!used[i] && d < best_d) {
        best_d = d;
        best = i;
      }
    }
    ASSERT_LT(best_d, 1e-6) << fc.tag << " cone at " << fc.x << ", " << fc.y;
    used[best] = true;
    const auto& cyl = standing["cylinders"][best];
    const bool big = fc.tag == "big_orange";
    EXPECT_NEAR(cyl["size"]["z"].get<double>(), big ? 0.505 : 0.325, 1e-9) << fc.tag;
    EXPECT_NEAR(cyl["size"]["x"].get<double>(), big ? 0.285 : 0.228, 1e-9) << fc.tag;
    EXPECT_NEAR(cyl["pose"]["position"]["z"].get<double>(), (big ? 0.505 : 0.325) / 2, 1e-9);  // flat ground
    const auto& col = cyl["color"];
    if (fc.tag == "blue") {
      EXPECT_GT(col["b"].get<double>(), col["r"].get<double>() + 0.5);
    }
    if (fc.tag == "yellow") {
      EXPECT_GT(col["g"].get<double>(), col["b"].get<double>() + 0.5);
    }
    EXPECT_LT(col["a"].get<double>(), 1.0);  // a ghost over the stack's own cone map
  }

  // The car has not moved: the true pose is the file's car_start.
  const auto state = pick("/truth/vehicle_state");
  ASSERT_TRUE(state);
  EXPECT_EQ((*state)["source"], "simulator ground truth");
  EXPECT_NEAR((*state)["x"].get<double>(), sx, 0.01);
  EXPECT_NEAR((*state)["y"].get<double>(), sy, 0.01);
  EXPECT_NEAR((*state)["yaw"].get<double>(), syaw, 0.01);
  EXPECT_NEAR((*state)["speed"].get<double>(), 0.0, 0.01);
  EXPECT_EQ((*state)["cones_hit"], 0);
  const auto car = pick("/truth/car");
  ASSERT_TRUE(car);
  EXPECT_EQ((*car)["entities"][0]["id"], "truth_car");
  EXPECT_NEAR((*car)["entities"][0]["arrows"][0]["pose"]["position"]["x"].get<double>(), sx, 0.01);
}

// The cone map as a viewer holds it (entity id → x, y), from SceneUpdates applied in order: deletions first (type
// 1 = all of the topic), then each entity replacing the one of its id.
using ConeView = std::map<std::string, std::pair<double, double>>;
void apply_scene(ConeView& view, const json& update, int* deletions = nullptr) {
  for (const auto& d : update["deletions"]) {
    if (d["type"] == 1) {
      view.clear();
    } else {
      view.erase(d["id"].get<std::string>());
      if (deletions) ++*deletions;
    }
  }
  for (const auto& e : update["entities"]) {
    const auto& p = e["cylinders"].at(0)["pose"]["position"];
    view[e["id"].get<std::string>()] = {p["x"].get<double>(), p["y"].get<double>()};
  }
}
// Applies every message of `sub` until none comes for a second; returns how many came.
int read_scene(WsClient& c, std::uint32_t sub, ConeView& view) {
  int n = 0;
  while (const auto m = next_on(c, sub, std::chrono::milliseconds(1000))) {
    apply_scene(view, *m);
    ++n;
  }
  return n;
}

// The cone map goes out as changes by cone: a client subscribed from the start and one that subscribes after the
// run both end with the Stack's own map (its ids and positions), the late one from a single message; a map that
// then changes by one moved and one removed cone reaches the early client as exactly that change.
TEST(Telemetry, EveryClientEndsWithTheStacksConeMapALateOneFromOneMessage) {
  LiveRun live(25.0);  // drives off at 5.5 s: cones come into view as it goes
  WsClient early(live.server->port());
  ASSERT_TRUE(early.handshake_ok());
  const auto subs = subscribe(early, {"/map/cones"});
  ASSERT_EQ(subs.size(), 1u);
  ASSERT_EQ(live.go(), 0);
  ConeView early_view;
  EXPECT_GE(read_scene(early, subs.at("/map/cones"), early_view), 1);

  WsClient late(live.server->port());
  ASSERT_TRUE(late.handshake_ok());
  // Subscribed without test::subscribe's sync round trip: waiting for its reply would skip the whole scene, which
  // comes first.
  const auto adv = late.next_op("advertise");
  ASSERT_TRUE(adv);
  for (const auto& ch : (*adv)["channels"])
    if (ch["topic"] == "/map/cones")
      late.send_text(json{{"op", "subscribe"}, {"subscriptions", {{{"id", 1}, {"channelId", ch["id"]}}}}}.dump());
  ConeView late_view;
  EXPECT_EQ(read_scene(late, 1, late_view), 1);

  // The truth: the Stack's map at the end of the run (the last snapshot is at most 3 cycles older).
  const auto& map = live.run->stack().cone_map();
  ASSERT_GT(map.size(), 30u);
  ConeView stack;
  for (std::size_t i = 0; i < map.size(); ++i)
    stack[map[i].id ? "cone/" + std::to_string(map[i].id) : "cone/#" + std::to_string(i)] = {map[i].position.x(),
                                                                                             map[i].position.y()};
  for (const auto* view : {&early_view, &late_view}) {
    ASSERT_EQ(view->size(), stack.size());
    for (const auto& [id, p] : stack) {
      ASSERT_TRUE(view->count(id)) << id;
      EXPECT_NEAR(view->at(id).first, p.first, 0.006) << id;  // sent to the cm
      EXPECT_NEAR(view->at(id).second, p.second, 0.006) << id;
    }
  }

  // Sent as changes: the map with its first cone moved 1 m and its last one gone arrives as that cone alone and
  // one deletion. (Counting the run's own updates would count wall time: the telemetry thread sends the newest
  // snapshot at 4 Hz, and a headless run lasts about a second.)
  auto changed = std::make_shared<std::vector<Cone>>(map);
  changed->front().position.x() += 1.0;
  changed->pop_back();
  auto snapshot = std::make_shared<TelemetrySnapshot>();
  snapshot->t = 100.0;
  snapshot->cone_map = changed;
  live.telemetry->publish(snapshot);
  const auto update = next_on(early, subs.at("/map/cones"), std::chrono::seconds(5));
  ASSERT_TRUE(update);
  ASSERT_EQ((*update)["entities"].size(), 1u) << update->dump();
  EXPECT_EQ((*update)["entities"][0]["id"], "cone/" + std::to_string(map.front().id));
  EXPECT_NEAR((*update)["entities"][0]["cylinders"][0]["pose"]["position"]["x"].get<double>(),
              map.front().position.x() + 1.0, 0.006);
  ASSERT_EQ((*update)["deletions"].size(), 1u) << update->dump();
  EXPECT_EQ((*update)["deletions"][0]["id"], "cone/" + std::to_string(map.back().id));
}

// On the LiDAR odometry the first lap's loop closes at the start's cones: a page opened after the run gets every
// loop closure the Stack applied (its time, lap and correction) in the latched list, and the localization channel
// names the source, without a covariance (the odometry gives none).
TEST(Telemetry, ALoopClosureReachesTheDashboardWithItsCorrection) {
  LiveRun live(45.0, [](Config& c) {
    c.set("sim.enable_lidar", true, "test");
    c.set("run.perception_source", std::string("lidar"), "test");
    c.set("run.localization_source", std::string("lidar_odometry"), "test");
  });
  ASSERT_EQ(live.go(), 0);
  const auto& closed = live.run->stack().loop_closures();
  ASSERT_FALSE(closed.empty()) << "no loop closed in 45 s: nothing to show";
  // Subscribed after the run (not through subscribe(), whose wait for its reply would pass over the latched message).
  WsClient c(live.server->port());
  ASSERT_TRUE(c.handshake_ok());
  const auto adv = c.next_op("advertise");
  ASSERT_TRUE(adv);
  for (const auto& ch : (*adv)["channels"])
    if (ch["topic"] == "/localization/loop_closures")
      c.send_text(json{{"op", "subscribe"}, {"subscriptions", {{{"id", 1}, {"channelId", ch["id"]}}}}}.dump());
  const auto m = next_on(c, 1);
  ASSERT_TRUE(m) << "no latched loop-closure list for a late subscriber";
  const auto& list = (*m)["loop_closures"];
  ASSERT_EQ(list.size(), closed.size());
  for (std::size_t i = 0; i < closed.size(); ++i) {
    EXPECT_DOUBLE_EQ(list[i]["t"].get<double>(), closed[i].t);
    EXPECT_EQ(list[i]["lap"], closed[i].lap);
    EXPECT_DOUBLE_EQ(list[i]["dx"].get<double>(), closed[i].correction.x);
    EXPECT_DOUBLE_EQ(list[i]["dyaw"].get<double>(), closed[i].correction.yaw);
    EXPECT_NEAR(list[i]["shift"].get<double>(), std::hypot(closed[i].correction.x, closed[i].correction.y), 1e-12);
    EXPECT_EQ(list[i]["pairs"], closed[i].pairs);
  }
}

TEST(Telemetry, PlanFallbacksAreCounted) {
  // Ten cycles: a plan on every other one; of the five, two on one boundary, one colour-blind as well, one with a
  // tight turn; a flag on a cycle without a plan counts nothing.
  web::Metrics registry;
  RunMetrics metrics(registry);
  for (int i = 0; i < 10; ++i) {
    CycleFigures f;
    f.t = 0.01 * i;
    f.planned = i % 2 == 0;
    f.planning_s = f.planned ? 0.001 : -1;
    f.plan_one_boundary = i == 0 || i == 2 || i == 3;
    f.plan_colour_blind = i == 2;
    f.plan_cut_short = i == 8 || i == 9;
    f.planning_cpu_s = f.planned ? 0.010 * i : -1;  // 0, 20, 40, 60, 80 ms against a 25 ms budget: three late
    f.late_plan = f.planned && f.planning_cpu_s > 0.025;
    metrics.on_cycle(f);
  }
  const auto m = parse_metrics(registry.render());
  EXPECT_EQ(m.at("fsd_plans_total"), 5);
  EXPECT_EQ(m.at("fsd_plans_one_boundary_total"), 2);
  EXPECT_EQ(m.at("fsd_plans_colour_blind_total"), 1);
  EXPECT_EQ(m.at("fsd_plans_cut_short_total"), 1);
  EXPECT_EQ(m.at("fsd_late_plans_total"), 3);
  EXPECT_EQ(m.at("fsd_planning_cpu_seconds_count"), 5);
  EXPECT_NEAR(m.at("fsd_planning_cpu_seconds_sum"), 0.2, 1e-9);
  EXPECT_NEAR(m.at("fsd_planning_cpu_seconds{quantile=\"0.5\"}"), 0.04, 1e-9);
}

TEST(Telemetry, MetricsOfARunAreScrapedOverHttp) {
  // 800 control cycles (10 ms), perception frames due at 0, 0.1, …, 8.0 s: 81; Ready at ≈ 0.5 s and RES go 5.5 s
  // later (the rules' 5 s in Ready + 0.5 s), so Driving at the end.
  LiveRun live(8.0);
  ASSERT_EQ(live.go(), 0);
  const auto res = web::test::http_request(live.server->port(), http::verb::get, "/metrics");
  ASSERT_EQ(res.status, 200u);
  EXPECT_NE(
      res.body.find("# HELP fsd_as_state AS state of the VCU: 0 Off, 1 Ready, 2 Driving, 3 Emergency, 4 Finished"),
      std::string::npos);
  const auto m = parse_metrics(res.body);
  auto at = [&](const std::string& key) {
    const auto it = m.find(key);
    EXPECT_NE(it, m.end()) << key << " missing from\n" << res.body;
    return it == m.end() ? NAN : it->second;
  };
  const std::string lat = "fsd_stage_latency_seconds";
  EXPECT_EQ(at("fsd_control_cycles_total"), 800);
  EXPECT_EQ(at(lat + "_count{stage=\"control\"}"), 800);
  EXPECT_EQ(at(lat + "_count{stage=\"perception\"}"), 81);
  EXPECT_EQ(at(lat + "_count{stage=\"end_to_end\"}"), 81);
  const double planned = at(lat + "_count{stage=\"planning\"}");
  EXPECT_GT(planned, 0);
  EXPECT_LE(planned, 800);
  EXPECT_EQ(at("fsd_plans_total"), planned);
  EXPECT_EQ(at("fsd_planning_cpu_seconds_count"), planned);
  EXPECT_LE(at("fsd_late_plans_total"), planned);
  // epfl_track_1 from its start: both boundaries in sight, colours right, no tight turn.
  EXPECT_EQ(at("fsd_plans_one_boundary_total"), 0);
  EXPECT_EQ(at("fsd_plans_colour_blind_total"), 0);
  EXPECT_EQ(at("fsd_plans_cut_short_total"), 0);
  for (const std::string stage : {"perception", "planning", "control", "end_to_end"}) {
    const double p50 = at(lat + "{stage=\"" + stage + "\",quantile=\"0.5\"}");
    const double p99 = at(lat + "{stage=\"" + stage + "\",quantile=\"0.99\"}");
    EXPECT_GT(p50, 0) << stage;
    EXPECT_LE(p50, p99) << stage;
    EXPECT_LT(p50, 0.05) << stage;  // a 10 ms loop
  }
  // End to end spans perception, planning and control of the same cycle.
  EXPECT_GE(at(lat + "{stage=\"end_to_end\",quantile=\"0.5\"}"), at(lat + "{stage=\"perception\",quantile=\"0.5\"}"));
  EXPECT_GT(at("fsd_control_period_seconds_count"), 700);
  EXPECT_EQ(at("fsd_as_state"), 2);
  EXPECT_EQ(at("fsd_as_state_active{state=\"Driving\"}"), 1);
  EXPECT_EQ(at("fsd_as_state_active{state=\"Ready\"}"), 0);
  EXPECT_NEAR(at("fsd_run_time_seconds"), 8.0, 1e-6);
  EXPECT_EQ(at("fsd_laps_completed"), 0);
  EXPECT_EQ(at("fsd_cones_hit"), 0);
  // Every 4th cycle hands a snapshot to telemetry; the lockstep loop outruns the telemetry thread, which skips.
  EXPECT_EQ(at("fsd_telemetry_snapshots_total"), 200);
  EXPECT_LE(at("fsd_telemetry_snapshots_skipped_total"), 199);
  EXPECT_EQ(at("fsd_web_clients"), 0);
  EXPECT_EQ(at("fsd_web_outbox_depth"), at("fsd_web_outbox_depth"));  // present (a number)
  // /api/state answers from the newest snapshot.
  const auto state = web::test::http_request(live.server->port(), http::verb::get, "/api/state");
  ASSERT_EQ(state.status, 200u);
  const auto s = json::parse(state.body);
  EXPECT_EQ(s["as_state"], "Driving");
  EXPECT_EQ(s["mission"], "trackdrive");
  EXPECT_GT(s["vehicle"]["speed"].get<double>(), 0.5);  // 2.5 s after go
}

TEST(Telemetry, LogLinesOfEveryLoggerReachTheLogChannel) {
  auto early = logger("telemetry_test_early");  // exists before the forwarding is attached
  RealClock clock;
  Config cfg(config_schema());
  ParamRegistry params(cfg, &clock);
  auto wc = web::web_section().read(cfg);
  wc.bind = "127.0.0.1";
  wc.port = 0;
  web::WebServer server(wc, params, clock);
  Telemetry telemetry(server);
  auto forwarding = std::make_unique<LogForwarding>(server, telemetry.channel(web::topics::kLog), clock);
  server.start();
  auto late = logger("telemetry_test_late");  // created afterwards: inherits the sink

  WsClient c(server.port());
  ASSERT_TRUE(c.handshake_ok());
  const auto subs = subscribe(c, {"/log"});
  ASSERT_EQ(subs.size(), 1u);
  const std::uint32_t sub = subs.at("/log");
  early->set_level(spdlog::level::debug);  // the sink's own level (info) must hold the debug line back
  early->info("early line {}", 1);
  late->warn("late line {}", 2);
  early->debug("below the level");

  std::map<std::string, json> got;
  while (got.size() < 2) {
    const auto m = next_on(c, sub);
    if (!m) break;
    if ((*m)["name"].get<std::string>().starts_with("telemetry_test_")) got[(*m)["message"].get<std::string>()] = *m;
  }
  ASSERT_EQ(got.count("early line 1"), 1u);
  ASSERT_EQ(got.count("late line 2"), 1u);
  EXPECT_EQ(got["early line 1"]["name"], "telemetry_test_early");
  EXPECT_EQ(got["early line 1"]["level"], 2);  // foxglove.Log INFO
  EXPECT_EQ(got["late line 2"]["level"], 3);   // WARNING

  forwarding->detach();
  early->info("after detach");
  late->info("after detach 2");  // neither may arrive
  while (const auto m = next_on(c, sub, std::chrono::milliseconds(300)))
    EXPECT_FALSE((*m)["name"].get<std::string>().starts_with("telemetry_test_")) << (*m)["message"];
  telemetry.stop();
  server.stop();
}

}  // namespace
}  // namespace fsd
