// Camera model output stream: JPEG frames at the configured rate, stamped capture time + latency, decoding to the
// configured resolution, deterministic for a seed and independent of how the simulation is stepped.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include <opencv2/imgcodecs.hpp>

#include "tests/sim/camera_test_util.hpp"
#include "tests/sim/world_test_util.hpp"

namespace fsd::sim {
namespace {

using test::make_cone;
using test::make_track;

struct Emitted {
  Stamp t;
  std::vector<std::uint8_t> bytes;
};

// The car drives along +x at 10 m/s.
Pose3 driving(Stamp t) { return Pose2{10.0 * t, 0.0, 0.0}.to_pose3(); }

std::vector<Emitted> run(const CameraConfig& cfg, const World& world, std::uint64_t seed, Stamp until, Stamp step) {
  CameraModel cam(cfg, world, seed);
  std::vector<Emitted> out;
  const ByteSink sink = [&](Stamp t, std::span<const std::uint8_t> b) { out.push_back({t, {b.begin(), b.end()}}); };
  for (int i = 0;; ++i) {
    const Stamp t = std::min(i * step, until);
    cam.advance_to(t, driving, sink);
    if (t >= until) break;
  }
  return out;
}

World make_world() {
  std::vector<TrackCone> cones;
  for (int i = 0; i < 10; ++i) {
    cones.push_back(make_cone(5.0 * i, 2.0, ConeRole::Left));
    cones.push_back(make_cone(5.0 * i, -2.0, ConeRole::Right));
  }
  WorldConfig wc;  // grass, texture and distractors as in a real run
  return World(make_track(cones), wc, 3);
}

TEST(CameraModelStream, FramesAtTheRateStampedWithLatencyDecodingToTheResolution) {
  const World world = make_world();
  for (const double rate : {20.0, 30.0}) {
    CameraConfig cfg;  // defaults: 640×480, noise, blur, lighting drift
    cfg.rate = rate;
    cfg.latency = 0.04;
    const auto frames = run(cfg, world, 1, 1.0, 0.1);
    // Captures at k/rate for k = 0 .. rate inside [0, 1].
    ASSERT_EQ(frames.size(), static_cast<std::size_t>(rate) + 1) << "rate " << rate;
    for (std::size_t k = 0; k < frames.size(); ++k) {
      EXPECT_NEAR(frames[k].t, k / rate + 0.04, 1e-9);
      const auto& b = frames[k].bytes;
      ASSERT_GT(b.size(), 4u);
      EXPECT_EQ(b[0], 0xFF);  // JPEG start-of-image marker FF D8
      EXPECT_EQ(b[1], 0xD8);
      EXPECT_EQ(b[b.size() - 2], 0xFF);  // end-of-image marker FF D9
      EXPECT_EQ(b[b.size() - 1], 0xD9);
    }
    const cv::Mat img = cv::imdecode(frames.back().bytes, cv::IMREAD_UNCHANGED);
    EXPECT_EQ(img.cols, 640);
    EXPECT_EQ(img.rows, 480);
    EXPECT_EQ(img.channels(), 3);
  }
}

TEST(CameraModelStream, OtherResolutionAndJpegQuality) {
  const World world = make_world();
  CameraConfig cfg;
  cfg.width = 320;
  cfg.height = 240;
  cfg.jpeg_quality = 30;
  const auto small = run(cfg, world, 1, 0.0, 0.1);
  ASSERT_EQ(small.size(), 1u);
  const cv::Mat img = cv::imdecode(small[0].bytes, cv::IMREAD_COLOR);
  EXPECT_EQ(img.size(), cv::Size(320, 240));
  cfg.jpeg_quality = 95;
  EXPECT_GT(run(cfg, world, 1, 0.0, 0.1)[0].bytes.size(), small[0].bytes.size()) << "higher quality, more bytes";
}

TEST(CameraModelStream, DeterministicForASeedWhateverTheStepping) {
  const World world = make_world();
  const CameraConfig cfg;
  const auto a = run(cfg, world, 5, 0.5, 0.1);
  const auto b = run(cfg, world, 5, 0.5, 0.013);
  const auto c = run(cfg, world, 6, 0.5, 0.1);
  ASSERT_EQ(a.size(), b.size());
  ASSERT_EQ(a.size(), c.size());
  for (std::size_t k = 0; k < a.size(); ++k) {
    EXPECT_EQ(a[k].t, b[k].t);
    EXPECT_EQ(a[k].bytes, b[k].bytes) << "frame " << k;
  }
  int differing = 0;
  for (std::size_t k = 0; k < a.size(); ++k) differing += a[k].bytes != c[k].bytes;
  EXPECT_EQ(differing, static_cast<int>(a.size())) << "another seed gives other noise";
}

TEST(CameraModelStream, ConsecutiveFramesShowTheMotion) {
  // Driving forward, the cones grow from frame to frame: the frame renders the pose at its capture time.
  const World world(make_track({make_cone(12.0, 0.0, ConeRole::Left)}), test::bare_config(), 1);
  CameraConfig cfg = test::plain_camera();
  const auto frames = run(cfg, world, 1, 0.5, 0.5);
  ASSERT_EQ(frames.size(), 11u);
  auto width_at = [&](std::size_t k) {
    const cv::Mat img = cv::imdecode(frames[k].bytes, cv::IMREAD_COLOR);
    return cv::boundingRect(test::hue_mask(img, 100, 130, 170)).width;
  };
  // At capture k the cone is 12 − 0.5·k m ahead: its base is 400·0.228/(12 − 0.5k) px wide, roughly.
  EXPECT_NEAR(width_at(0), 400 * 0.228 / 12.0, 2.0);
  EXPECT_NEAR(width_at(10), 400 * 0.228 / 7.0, 2.0);
}

}  // namespace
}  // namespace fsd::sim
