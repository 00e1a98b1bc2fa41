// Speed of the virtual VLP-16: simulated seconds of sensor output per wall-clock second on one core, with the car
// driving the centre of epfl_track_1 at 10 m/s among the cones and the default distractors.
// Run from the project root:  build/bench/lidar_sim_bench
// "sim_s_per_s" is the real-time factor of the LiDAR model alone per second of CPU time on one core (the whole
// virtual car aims at ≥ 5×); CPU time rather than wall time so a busy machine does not distort it.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

#include "common/track.hpp"
#include "drivers/sim/sensors/lidar_model.hpp"
#include "drivers/sim/world/world.hpp"

namespace {

using namespace fsd;
using namespace fsd::sim;

const Track& bench_track() {
  static const Track t = load_track("../shared/tracks/epfl_track_1.csv");
  return t;
}

// Centre line: each blue cone paired with its nearest yellow one, in file order.
std::vector<Vec2> centre_line(const Track& track) {
  std::vector<Vec2> left, right, mid;
  for (const auto& c : track.cones) {
    if (c.role == ConeRole::Left) left.push_back(c.position);
    if (c.role == ConeRole::Right) right.push_back(c.position);
  }
  for (const auto& l : left) {
    Vec2 best = right.front();
    for (const auto& r : right)
      if ((r - l).norm() < (best - l).norm()) best = r;
    mid.push_back((l + best) / 2);
  }
  return mid;
}

// Body pose driving along a closed polyline at constant speed.
class Drive {
 public:
  Drive(std::vector<Vec2> path, double speed) : path_(std::move(path)), speed_(speed) {
    s_.push_back(0);
    for (std::size_t i = 0; i < path_.size(); ++i)
      s_.push_back(s_.back() + (path_[(i + 1) % path_.size()] - path_[i]).norm());
  }
  Pose3 operator()(Stamp t) const {
    const double s = std::fmod(speed_ * t, s_.back());
    std::size_t i = 0;
    while (s_[i + 1] < s) ++i;
    const Vec2 a = path_[i], b = path_[(i + 1) % path_.size()];
    const double f = (s - s_[i]) / (s_[i + 1] - s_[i]);
    const Vec2 p = a + f * (b - a);
    return Pose2{p.x(), p.y(), std::atan2(b.y() - a.y(), b.x() - a.x())}.to_pose3();
  }

 private:
  std::vector<Vec2> path_;
  std::vector<double> s_;
  double speed_;
};

void BM_Vlp16SimulatedSecond(benchmark::State& state) {
  WorldConfig wc;
  wc.distractors = state.range(0) != 0;
  const World world(bench_track(), wc, 1);
  const Drive drive(centre_line(bench_track()), 10.0);
  LidarModel lidar(LidarConfig{}, world, 1);
  std::uint64_t returns = 0;
  Stamp t = 0;
  const ByteSink sink = [&](Stamp, std::span<const std::uint8_t> p) { returns += p[3] != 0; };
  for (auto _ : state) {
    t += 1.0;
    lidar.advance_to(t, std::cref(drive), sink);
  }
  benchmark::DoNotOptimize(returns);
  state.counters["sim_s_per_s"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["rays_per_s"] =
      benchmark::Counter(static_cast<double>(lidar.packets_sent()) * 384.0, benchmark::Counter::kIsRate);
  state.counters["distractors"] = static_cast<double>(world.distractors().size());
}
BENCHMARK(BM_Vlp16SimulatedSecond)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond);

// Raycast cost against the number of objects: a grid index keeps it flat.
void BM_RaycastVsObjectCount(benchmark::State& state) {
  WorldConfig wc;
  wc.tyres = static_cast<int>(state.range(0));
  wc.posts = static_cast<int>(state.range(0));
  wc.tyre_stacks = static_cast<int>(state.range(0));
  const World world(bench_track(), wc, 1);
  const Drive drive(centre_line(bench_track()), 10.0);
  std::vector<Pose3> poses;
  for (int i = 0; i < 1000; ++i) poses.push_back(drive(i * 0.1));
  std::size_t k = 0, hits = 0;
  for (auto _ : state) {
    const Pose3& pose = poses[k % poses.size()];
    const double a = static_cast<double>(k % 1800) * 0.2 * std::numbers::pi / 180.0;
    const double e = deg2rad(-15.0 + 2.0 * static_cast<double>(k % 16));
    const Vec3 dir = pose.linear() * Vec3(std::cos(e) * std::cos(a), -std::cos(e) * std::sin(a), std::sin(e));
    hits += world.raycast(pose * Vec3(2.0, 0, 0.35), dir, 100.0).has_value();
    ++k;
  }
  benchmark::DoNotOptimize(hits);
  state.counters["objects"] = static_cast<double>(world.cones().size() + world.distractors().size());
}
BENCHMARK(BM_RaycastVsObjectCount)->Arg(0)->Arg(10)->Arg(100)->Arg(400);

void BM_WorldConstruction(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(World(bench_track(), WorldConfig{}, 1).distractors().size());
}
BENCHMARK(BM_WorldConstruction)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
