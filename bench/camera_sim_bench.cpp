// Speed of the virtual car's camera (drivers/sim/sensors/camera_model.hpp) on epfl_track_1 at the default configuration
// (640×480, 20 Hz, noise, blur, shadows, distractors), on one core: OpenCV's own threads are switched off.
//   build/bench/camera_sim_bench
// items_per_second is frames per second of CPU time; x_realtime divides it by the 20 Hz frame rate.
#include <benchmark/benchmark.h>

#include <cmath>
#include <limits>
#include <memory>
#include <vector>

#include <opencv2/core.hpp>

#include "common/track.hpp"
#include "drivers/sim/sensors/camera_model.hpp"

namespace {

using namespace fsd;
using namespace fsd::sim;

struct Scene {
  Track track = load_track("../shared/tracks/epfl_track_1.csv");
  World world{track, WorldConfig{}, 1};
  CameraConfig cfg;
  std::vector<Pose3> poses;  // along the centre line, heading to the next point

  Scene() {
    cv::setNumThreads(1);
    std::vector<Vec2> mid;
    for (const auto& left : track.cones) {
      if (left.role != ConeRole::Left) continue;
      double best = std::numeric_limits<double>::max();
      Vec2 partner = left.position;
      for (const auto& right : track.cones)
        if (right.role == ConeRole::Right && (right.position - left.position).norm() < best) {
          best = (right.position - left.position).norm();
          partner = right.position;
        }
      mid.push_back((left.position + partner) / 2);
    }
    for (std::size_t i = 0; i < mid.size(); ++i) {
      const Vec2 d = mid[(i + 1) % mid.size()] - mid[i];
      poses.push_back(Pose2{mid[i].x(), mid[i].y(), std::atan2(d.y(), d.x())}.to_pose3());
    }
  }
};

Scene& scene() {
  static Scene s;
  return s;
}

void report(benchmark::State& state, double rate) {
  state.SetItemsProcessed(state.iterations());
  state.counters["x_realtime"] =
      benchmark::Counter(static_cast<double>(state.iterations()) / rate, benchmark::Counter::kIsRate);
}

void BM_CameraModelSetup(benchmark::State& state) {
  Scene& s = scene();
  for (auto _ : state) {
    CameraModel cam(s.cfg, s.world, 1);
    benchmark::DoNotOptimize(&cam);
  }
}
BENCHMARK(BM_CameraModelSetup)->Unit(benchmark::kMillisecond)->Iterations(3);

void BM_CameraRender(benchmark::State& state) {
  Scene& s = scene();
  const CameraModel cam(s.cfg, s.world, 1);
  std::size_t i = 0;
  for (auto _ : state) {
    cv::Mat img = cam.render(s.poses[i % s.poses.size()], 0.05 * static_cast<double>(i));
    benchmark::DoNotOptimize(img.data);
    ++i;
  }
  report(state, s.cfg.rate);
}
BENCHMARK(BM_CameraRender)->Unit(benchmark::kMillisecond);

// What the simulation pays per frame: rendering plus JPEG encoding, through advance_to.
void BM_CameraFrameWithJpeg(benchmark::State& state) {
  Scene& s = scene();
  CameraModel cam(s.cfg, s.world, 1);
  std::size_t bytes = 0;
  for (auto _ : state) {
    const Stamp t = cam.next_capture();
    const Pose3 pose = s.poses[cam.frames_sent() % s.poses.size()];
    cam.advance_to(
        t, [&](Stamp) { return pose; }, [&](Stamp, std::span<const std::uint8_t> b) { bytes += b.size(); });
  }
  report(state, s.cfg.rate);
  state.counters["jpeg_kB"] = static_cast<double>(bytes) / 1000.0 / static_cast<double>(state.iterations());
}
BENCHMARK(BM_CameraFrameWithJpeg)->Unit(benchmark::kMillisecond);

void BM_CameraVisibleCones(benchmark::State& state) {
  Scene& s = scene();
  const CameraModel cam(s.cfg, s.world, 1);
  std::size_t i = 0, cones = 0;
  for (auto _ : state) {
    const auto v = cam.visible_cones(s.poses[i++ % s.poses.size()]);
    cones += v.size();
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["cones_per_frame"] = static_cast<double>(cones) / static_cast<double>(state.iterations());
}
BENCHMARK(BM_CameraVisibleCones)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
