// JPEG frames: decoding what an MJPEG camera and the virtual car's camera send, rejecting broken transfers.
#include <gtest/gtest.h>

#include <vector>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "drivers/camera/jpeg_frame.hpp"
#include "drivers/sim/sensors/camera_model.hpp"

namespace fsd {
namespace {

std::vector<std::uint8_t> encode(const cv::Mat& img, const std::string& ext = ".jpg") {
  std::vector<std::uint8_t> out;
  EXPECT_TRUE(cv::imencode(ext, img, out));
  return out;
}

cv::Mat test_image() {
  cv::Mat img(120, 160, CV_8UC3, cv::Scalar(30, 140, 220));  // B, G, R
  cv::rectangle(img, cv::Rect(40, 30, 40, 60), cv::Scalar(200, 60, 20), cv::FILLED);
  return img;
}

void expect_rejected(const std::vector<std::uint8_t>& bytes, const std::string& needle) {
  try {
    decode_jpeg_frame(bytes, 0.0);
    ADD_FAILURE() << "accepted, expected: " << needle;
  } catch (const CameraDataError& e) {
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
  }
}

TEST(JpegFrame, DecodesToBgrWithStampAndSequence) {
  const auto bytes = encode(test_image());
  const Frame f = decode_jpeg_frame(bytes, 12.5, 7);
  EXPECT_EQ(f.stamp, 12.5);
  EXPECT_EQ(f.seq, 7u);
  ASSERT_EQ(f.bgr.size(), cv::Size(160, 120));
  ASSERT_EQ(f.bgr.type(), CV_8UC3);
  // Flat areas come back with their colour (JPEG error of a few levels), channel order B, G, R.
  const cv::Vec3b bg = f.bgr.at<cv::Vec3b>(10, 140), box = f.bgr.at<cv::Vec3b>(60, 60);
  EXPECT_NEAR(bg[0], 30, 6);
  EXPECT_NEAR(bg[1], 140, 6);
  EXPECT_NEAR(bg[2], 220, 6);
  EXPECT_NEAR(box[0], 200, 6);
  EXPECT_NEAR(box[2], 20, 6);
}

TEST(JpegFrame, AcceptsZeroPaddingAfterTheEndMarker) {
  auto bytes = encode(test_image());
  bytes.insert(bytes.end(), 8, 0x00);
  EXPECT_EQ(decode_jpeg_frame(bytes, 0.0).bgr.size(), cv::Size(160, 120));
}

TEST(JpegFrame, RejectsBrokenInput) {
  const auto good = encode(test_image());
  expect_rejected({}, "no data");
  expect_rejected(std::vector<std::uint8_t>(good.begin(), good.begin() + good.size() / 2), "truncated");
  expect_rejected(encode(test_image(), ".png"), "start-of-image");
  expect_rejected({0xFF, 0xD8}, "start-of-image");
  auto junk_after = good;
  junk_after.insert(junk_after.end(), {0x12, 0x34});
  expect_rejected(junk_after, "end-of-image");
  // Headers wiped out after the start marker: markers intact at both ends, nothing decodable between.
  auto wiped = good;
  std::fill(wiped.begin() + 3, wiped.end() - 2, 0x00);
  expect_rejected(wiped, "corrupt");
  std::vector<std::uint8_t> huge(kMaxJpegBytes + 1, 0);
  expect_rejected(huge, "limit");
}

TEST(JpegFrame, DecodesTheVirtualCarsCamera) {
  Track track;
  sim::WorldConfig wc;
  wc.distractors = false;
  const sim::World world(track, wc, 1);
  sim::CameraConfig cfg;  // 640×480 at 20 Hz, 30 ms latency
  sim::CameraModel cam(cfg, world, 1);
  std::vector<Frame> frames;
  std::uint32_t seq = 0;
  cam.advance_to(
      0.1, [](Stamp) { return Pose3::Identity(); },
      [&](Stamp t, std::span<const std::uint8_t> b) { frames.push_back(decode_jpeg_frame(b, t, seq++)); });
  ASSERT_EQ(frames.size(), 3u);
  EXPECT_DOUBLE_EQ(frames[2].stamp, 0.1 + cfg.latency);
  EXPECT_EQ(frames[2].bgr.size(), cv::Size(640, 480));
}

}  // namespace
}  // namespace fsd
