// Planning and following time per call on epfl_track_1 (Google Benchmark; p50/p99 as counters, in µs).
//   Planning: lap 1's real-time planner (corridor walk + path optimizer + the body's sweep + speed profile) with the
//   whole track's cones as the map, the car at every centre-line rung (nearest left/right cone midpoints) facing
//   along the track at 6 m/s. Its budget: p99 ≤ 15 ms on one core (the counters are CPU time of the thread).
//   Following: one follow() call on the lap-2 path (the smoothed closed centre line) and on a real-time plan,
//   for each steering law, the car stepping round the lap.
//   Lap build: lap 2's path from lap 1's recorded poses (the centre line driven at 0.3 m spacing) and the map,
//   on the centre line or the minimum-curvature line: once per run, on the control thread.
//   Skid pad fit: the figure of eight's two ring fits (vote + Gauss-Newton) on amz_fssim_skidpad's cones, all of
//   them and those within 20 m of the start (the view from the entry): on the control thread, each fresh map until
//   the car drives the left circle.
//   Run: build/bench/control_bench  (from the project root, so that ../shared resolves)
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <vector>

#include "common/thread_cpu.hpp"
#include "common/track.hpp"
#include "control/missions/skidpad.hpp"
#include "control/planning/realtime_planner.hpp"
#include "control/planning/recorded_trajectory.hpp"
#include "control/planning/smoothing.hpp"
#include "control/tracking/follower.hpp"

namespace fsd {
namespace {

struct Fixture {
  Track track = load_track("../shared/tracks/epfl_track_1.csv");
  std::vector<Cone> cones;
  std::vector<Pose2> poses;  // along the centre line, facing along the track
  Path lap;                  // closed centre line
  Fixture() {
    std::vector<Vec2> left, right;
    cones = cones_of(track);
    for (const auto& c : track.cones) {
      if (c.role == ConeRole::Left) left.push_back(c.position);
      if (c.role == ConeRole::Right) right.push_back(c.position);
    }
    lap.closed = true;
    for (const auto& l : left) {
      const Vec2* best = &right.front();
      for (const auto& r : right)
        if ((r - l).norm() < (*best - l).norm()) best = &r;
      const Vec2 across = (l - *best).normalized();  // right → left
      const Vec2 mid = 0.5 * (l + *best);
      poses.push_back({mid.x(), mid.y(), std::atan2(-across.x(), across.y())});
      lap.points.push_back({mid, 0, 0, 0, 0});
    }
    lap = smooth_path(lap, 0.25, 8.0);
    // Facing along the centre line (a rung's own heading can point at a boundary cone a nose ahead).
    for (auto& p : poses)
      if (const auto f = project(lap, p.position())) p.yaw = f->yaw;
    SpeedLimits limits;
    limits.mu = 1.1;
    SpeedProfile(limits).apply(lap, 0, 0);
  }
};

const Fixture& fixture() {
  static const Fixture f;
  return f;
}

// CPU time of this thread, µs: what a plan costs, without the time the thread waited for a core.
double thread_cpu_us() { return 1e6 * thread_cpu_seconds(); }

void report(benchmark::State& state, std::vector<double>& us) {
  if (us.empty()) return;
  std::sort(us.begin(), us.end());
  auto pct = [&](double p) { return us[std::min(us.size() - 1, static_cast<std::size_t>(p * us.size()))]; };
  state.counters["p50_us"] = pct(0.50);
  state.counters["p99_us"] = pct(0.99);
  state.counters["max_us"] = us.back();
}

void BM_RealtimePlan(benchmark::State& state) {
  const Fixture& f = fixture();
  PlannerConfig config;
  config.walk.use_colours = state.range(0) != 0;
  const RealtimePlanner planner(config, PathConfig{}, f.track.convention, SpeedLimits{});
  std::vector<double> us;
  std::size_t i = 0, failed = 0;
  for (auto _ : state) {
    VehicleState s;
    s.pose = f.poses[i++ % f.poses.size()];
    s.vx = 6.0;
    const double t0 = thread_cpu_us();
    const PlanResult r = planner.plan(f.cones, s);
    us.push_back(thread_cpu_us() - t0);
    failed += !r.ok;
    benchmark::DoNotOptimize(r);
  }
  report(state, us);
  state.counters["failed"] = static_cast<double>(failed);
}
BENCHMARK(BM_RealtimePlan)->Arg(1)->Arg(0)->ArgName("colours")->Iterations(500)->Unit(benchmark::kMicrosecond);

void BM_SkidpadFit(benchmark::State& state) {
  const Track t = load_track("../shared/tracks/amz_fssim_skidpad.csv");
  std::vector<Cone> cones;
  for (const Cone& c : cones_of(t))
    if (state.range(0) == 0 || (c.position.head<2>() - t.start.position()).norm() <= 20.0) cones.push_back(c);
  std::vector<double> us;
  std::size_t failed = 0;
  for (auto _ : state) {
    const double t0 = thread_cpu_us();
    const auto g = fit_skidpad(cones, t.start, t.convention);
    us.push_back(thread_cpu_us() - t0);
    failed += !g;
    benchmark::DoNotOptimize(g);
  }
  report(state, us);
  state.counters["failed"] = static_cast<double>(failed);
}
BENCHMARK(BM_SkidpadFit)->Arg(0)->Arg(1)->ArgName("entry_view")->Iterations(300)->Unit(benchmark::kMicrosecond);

void BM_Follow(benchmark::State& state) {
  const Fixture& f = fixture();
  FollowerConfig config;
  config.type = state.range(0) == 0 ? "pure_pursuit" : state.range(0) == 1 ? "stanley" : "lqr";
  const bool on_plan = state.range(1) != 0;
  PathFollower follower(config);
  const RealtimePlanner planner({}, PathConfig{}, f.track.convention, SpeedLimits{});
  std::vector<double> us;
  std::size_t i = 0;
  Path plan;
  for (auto _ : state) {
    VehicleState s;
    s.pose = f.poses[i % f.poses.size()];
    s.pose.x += 0.2;  // a little off the line
    s.vx = 8.0;
    s.steering = 0.05;
    if (on_plan && (i % 10 == 0 || plan.empty())) {  // a new plan every tenth cycle, as at 10 Hz / 100 Hz
      state.PauseTiming();
      plan = planner.plan(f.cones, s).path;
      state.ResumeTiming();
    }
    ++i;
    const auto t0 = std::chrono::steady_clock::now();
    const FollowResult r = follower.follow(on_plan ? plan : f.lap, s, 0.0, 20.0);
    us.push_back(std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count());
    benchmark::DoNotOptimize(r);
  }
  report(state, us);
}
BENCHMARK(BM_Follow)
    ->ArgsProduct({{0, 1, 2}, {0, 1}})
    ->ArgNames({"law", "on_plan"})
    ->Iterations(20000)
    ->Unit(benchmark::kMicrosecond);

void BM_LapBuild(benchmark::State& state) {
  const Fixture& f = fixture();
  RecordedTrajectoryConfig config;
  config.line = state.range(0) != 0 ? "min_curvature" : "centre";
  RecordedTrajectory rec(config);
  double t = 0;
  for (const auto& q : f.lap.points) {
    VehicleState s;
    s.stamp = t += 0.05;
    s.pose = {q.p.x(), q.p.y(), q.yaw};
    rec.record(s);
  }
  SpeedLimits limits;
  limits.mu = 1.2;
  const SpeedProfile profile(limits);
  std::vector<double> us;
  for (auto _ : state) {
    const double t0 = thread_cpu_us();
    const auto r = rec.build(0, t, f.cones, f.track.convention, profile);
    us.push_back(thread_cpu_us() - t0);
    if (!r.path) state.SkipWithError(r.reason.c_str());
    benchmark::DoNotOptimize(r);
  }
  report(state, us);
}
BENCHMARK(BM_LapBuild)->Arg(0)->Arg(1)->ArgName("min_curvature")->Iterations(20)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace fsd

BENCHMARK_MAIN();
