// Camera driver on a real video file (MJPG in AVI, written here with OpenCV): every frame arrives once, in order,
// with its content, stamp and sequence number; files end or loop; a missing source is retried; stop is clean.
#include <gtest/gtest.h>

#include <filesystem>

#include <nlohmann/json.hpp>

#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

#include "drivers/camera/camera_source.hpp"
#include "tests/scratch_dir.hpp"

namespace fsd {
namespace {

namespace fs = std::filesystem;
using std::chrono::milliseconds;

constexpr int kFrames = 12;
constexpr int kWidth = 160, kHeight = 120;

// Frame k is a flat grey of level 20·k: easy to recognise after JPEG.
int level_of(int k) { return 20 * k; }

class CameraSourceFile : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = test::scratch_path(::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
    video_ = (dir_ / "clip.avi").string();
    cv::VideoWriter w(video_, cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), 20.0, cv::Size(kWidth, kHeight));
    if (!w.isOpened()) GTEST_SKIP() << "this OpenCV cannot write MJPG/AVI";
    for (int k = 0; k < kFrames; ++k) w.write(cv::Mat(kHeight, kWidth, CV_8UC3, cv::Scalar::all(level_of(k))));
    w.release();
  }
  void TearDown() override { fs::remove_all(dir_); }

  CameraDriverConfig file_config() const {
    CameraDriverConfig c;
    c.source = video_;
    c.width = kWidth;
    c.height = kHeight;
    c.fps = 200.0;  // paced playback, quick
    c.latency = 0.02;
    c.reconnect_delay = 0.05;
    return c;
  }

  // Takes frames until the source reports the end of the file (or a generous deadline for a stuck test).
  static std::vector<Frame> drain(CameraSource& src) {
    std::vector<Frame> got;
    for (int polls = 0; polls < 500; ++polls) {
      if (auto f = src.next_frame(milliseconds(20)))
        got.push_back(*f);
      else if (src.stats().finished)
        break;
    }
    return got;
  }

  fs::path dir_;
  std::string video_;
};

TEST_F(CameraSourceFile, ReadsEveryFrameOnceInOrderWithItsContent) {
  LockstepClock clock(5.0);  // time stands still: every stamp is 5.0 − latency
  CameraSource src(file_config(), clock);
  src.start();
  const auto got = drain(src);
  const CameraStats st = src.stats();
  src.stop();

  EXPECT_TRUE(st.finished);
  EXPECT_EQ(st.frames, static_cast<std::uint64_t>(kFrames));
  EXPECT_EQ(got.size() + st.dropped, static_cast<std::size_t>(kFrames)) << "each frame taken or counted as dropped";
  ASSERT_FALSE(got.empty());
  EXPECT_EQ(got.back().seq, static_cast<std::uint32_t>(kFrames - 1)) << "the last frame is never lost";
  for (std::size_t i = 0; i < got.size(); ++i) {
    const Frame& f = got[i];
    if (i > 0) {
      EXPECT_GT(f.seq, got[i - 1].seq);
    }
    EXPECT_DOUBLE_EQ(f.stamp, 5.0 - 0.02);
    ASSERT_EQ(f.bgr.size(), cv::Size(kWidth, kHeight));
    ASSERT_EQ(f.bgr.type(), CV_8UC3);
    const cv::Scalar mean = cv::mean(f.bgr);
    EXPECT_NEAR(mean[1], level_of(static_cast<int>(f.seq)), 3.0) << "frame " << f.seq;
  }
  EXPECT_EQ(st.size_mismatches, 0u);
  EXPECT_FALSE(src.next_frame(milliseconds(10))) << "nothing after the end";
}

TEST_F(CameraSourceFile, LoopingFileKeepsDelivering) {
  LockstepClock clock(0.0);
  CameraDriverConfig cfg = file_config();
  cfg.loop_file = true;
  cfg.pace_file = false;
  CameraSource src(cfg, clock);
  src.start();
  std::uint32_t highest = 0;
  for (int polls = 0; polls < 1000 && highest < 3 * kFrames; ++polls)
    if (auto f = src.next_frame(milliseconds(20))) highest = std::max(highest, f->seq);
  src.stop();
  EXPECT_GE(highest, static_cast<std::uint32_t>(3 * kFrames)) << "three passes through a 12-frame file";
  EXPECT_FALSE(src.stats().finished);
}

TEST_F(CameraSourceFile, ConfiguredSizeMismatchIsCounted) {
  LockstepClock clock(0.0);
  CameraDriverConfig cfg = file_config();
  cfg.width = 640;
  cfg.height = 480;
  CameraSource src(cfg, clock);
  src.start();
  const auto got = drain(src);
  src.stop();
  EXPECT_EQ(src.stats().size_mismatches, static_cast<std::uint64_t>(kFrames));
  ASSERT_FALSE(got.empty());
  EXPECT_EQ(got.back().bgr.size(), cv::Size(kWidth, kHeight)) << "frames pass through as they are";
}

TEST(CameraSource, MissingSourceIsRetriedAndStopsCleanly) {
  LockstepClock clock(0.0);
  CameraDriverConfig cfg;
  cfg.source = test::scratch_path("no_such_video.avi");
  cfg.reconnect_delay = 0.02;
  CameraSource src(cfg, clock);
  src.start();
  for (int polls = 0; polls < 500 && src.stats().open_failures < 3; ++polls) src.next_frame(milliseconds(10));
  src.stop();
  const CameraStats st = src.stats();
  EXPECT_GE(st.open_failures, 3u);
  EXPECT_EQ(st.frames, 0u);
  EXPECT_FALSE(st.open);
  src.stop();  // idempotent
}

TEST(CameraSource, ConfigSectionDefaultsAndBounds) {
  auto schema = std::make_shared<ConfigSchema>();
  camera_driver_section().describe(*schema);
  Config cfg(schema);
  const CameraDriverConfig d = camera_driver_section().read(cfg);
  EXPECT_EQ(d.source, "/dev/video0");
  EXPECT_EQ(d.width, 640);
  EXPECT_EQ(d.fourcc, "MJPG");
  EXPECT_TRUE(d.calibration.empty());
  cfg.set("drivers.camera.source", "v4l2src ! videoconvert ! appsink", "test");
  EXPECT_EQ(camera_driver_section().read(cfg).source, "v4l2src ! videoconvert ! appsink");
  EXPECT_THROW(cfg.set("drivers.camera.fourcc", "H264", "test"), ConfigError);
  EXPECT_THROW(cfg.set("drivers.camera.fps", 0.0, "test"), ConfigError);
}

TEST(CameraSource, SourcesAreClassifiedByTheirForm) {
  EXPECT_EQ(classify_camera_source("/dev/video0"), CameraSourceKind::Device);
  EXPECT_EQ(classify_camera_source("2"), CameraSourceKind::Device);
  EXPECT_EQ(classify_camera_source("v4l2src device=/dev/video1 ! videoconvert ! appsink"), CameraSourceKind::Pipeline);
  EXPECT_EQ(classify_camera_source("runs/lap1.avi"), CameraSourceKind::File);
  EXPECT_EQ(classify_camera_source("rtsp://10.0.0.5/stream"), CameraSourceKind::File);  // FFmpeg opens URLs
}

}  // namespace
}  // namespace fsd
