// Split mode's inputs from the network (daemon/dds/ros_messages): what the daemon refuses before it uses any of a
// sample, and that a stamp crosses as Unix time and comes back on the reader's own run clock.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <string>
#include <variant>

#include "daemon/dds/checked_type.hpp"
#include "daemon/dds/ros_messages.hpp"
#include "daemon/dds/ros_time.hpp"
#include "fsd_msgs/msg/ConeDetectionsPubSubTypes.h"

namespace fsd::dds {
namespace {

fsd_msgs::msg::dds_::ConeDetections_ frame_with_one_cone() {
  fsd_msgs::msg::dds_::ConeDetections_ m;
  m.header().frame_id("base_link");
  m.header().stamp().sec(1800000000);
  m.header().stamp().nanosec(250000000);
  fsd_msgs::msg::dds_::DetectedCone_ c;
  c.position().x(5.0);
  c.position().y(-1.5);
  c.covariance() = {0.01, 0, 0, 0.01};
  c.colour(2);  // yellow
  c.confidence(0.9);
  c.colour_confidence(0.8);
  c.colour_source(2);  // camera
  c.stage(2);          // camera
  c.points(12);
  m.cones().push_back(c);
  return m;
}

std::string refusal(const Checked<RemoteDetections>& c) {
  const auto* why = std::get_if<std::string>(&c);
  return why ? *why : "";
}

TEST(DdsMessages, AWholePerceptionFrameIsTakenOnTheReadersClock) {
  // The sender's Unix time 1800000000.25; this run's clock started at Unix 1800000000.0: the frame is at 0.25 s.
  const auto got = from_detections(frame_with_one_cone(), 1800000000.0);
  ASSERT_TRUE(std::holds_alternative<RemoteDetections>(got)) << refusal(got);
  const auto& d = std::get<RemoteDetections>(got).detections;
  EXPECT_NEAR(d.stamp, 0.25, 1e-6);
  ASSERT_EQ(d.cones.size(), 1u);
  EXPECT_EQ(d.cones[0].colour, ConeColour::Yellow);
  EXPECT_EQ(d.cones[0].stage, DetectionStage::Camera);
  EXPECT_DOUBLE_EQ(d.cones[0].position.x(), 5.0);
  EXPECT_EQ(d.cones[0].points, 12u);
}

TEST(DdsMessages, APerceptionFrameWithAnyBadFieldIsRefusedWhole) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  struct Case {
    const char* what;
    std::function<void(fsd_msgs::msg::dds_::ConeDetections_&)> spoil;
    const char* says;
  };
  const Case cases[] = {
      {"NaN position", [&](auto& m) { m.cones()[0].position().x(nan); }, "position"},
      {"far away", [](auto& m) { m.cones()[0].position().y(1e9); }, "position"},
      {"infinite covariance", [](auto& m) { m.cones()[0].covariance()[3] = INFINITY; }, "covariance"},
      {"unknown colour", [](auto& m) { m.cones()[0].colour(9); }, "colour"},
      {"unknown stage", [](auto& m) { m.cones()[0].stage(7); }, "stage"},
      {"confidence above 1", [](auto& m) { m.cones()[0].confidence(1.5); }, "confidence"},
      {"NaN confidence", [&](auto& m) { m.cones()[0].colour_confidence(nan); }, "confidence"},
      {"map frame", [](auto& m) { m.header().frame_id("map"); }, "frame_id"},
      {"nanoseconds past a second", [](auto& m) { m.header().stamp().nanosec(1000000000u); }, "nanosec"},
      {"too many cones", [](auto& m) { m.cones().resize(kMaxRemoteCones + 1, m.cones()[0]); }, "more than"},
      {"a bad rejected cone",
       [&](auto& m) {
         m.camera_rejected().push_back(m.cones()[0]);
         m.camera_rejected()[0].position().z(nan);
       },
       "position"},
  };
  for (const auto& c : cases) {
    auto m = frame_with_one_cone();
    c.spoil(m);
    const auto got = from_detections(m, 1800000000.0);
    EXPECT_NE(refusal(got).find(c.says), std::string::npos) << c.what << ": " << refusal(got);
  }
}

TEST(DdsMessages, APoseNeedsTheMapFrameAndAUnitQuaternion) {
  nav_msgs::msg::dds_::Odometry_ m;
  m.header().frame_id("map");
  m.pose().pose().position().x(3.0);
  m.pose().pose().orientation().z(std::sin(0.3));
  m.pose().pose().orientation().w(std::cos(0.3));  // yaw 0.6
  const auto ok = from_odometry(m, 0.0);
  ASSERT_TRUE(std::holds_alternative<RemotePose>(ok));
  EXPECT_NEAR(std::get<RemotePose>(ok).pose.yaw, 0.6, 1e-12);
  auto bad = m;
  bad.pose().pose().orientation().w(0.5);
  EXPECT_TRUE(std::holds_alternative<std::string>(from_odometry(bad, 0.0)));
  bad = m;
  bad.header().frame_id("odom");
  EXPECT_TRUE(std::holds_alternative<std::string>(from_odometry(bad, 0.0)));
  bad = m;
  bad.pose().pose().position().y(std::numeric_limits<double>::infinity());
  EXPECT_TRUE(std::holds_alternative<std::string>(from_odometry(bad, 0.0)));
}

TEST(DdsMessages, ACameraFrameMustBeAJpegOfBoundedSize) {
  sensor_msgs::msg::dds_::CompressedImage_ m;
  m.format("jpeg");
  m.data({0xFF, 0xD8, 0xFF, 0xE0, 0x00});
  EXPECT_TRUE(
      std::holds_alternative<RemoteImage>(from_compressed_image(sensor_msgs::msg::dds_::CompressedImage_(m), 0)));
  auto png = m;
  png.format("png");
  EXPECT_TRUE(std::holds_alternative<std::string>(from_compressed_image(std::move(png), 0)));
  auto not_jpeg = m;
  not_jpeg.data({0x89, 'P', 'N', 'G', 0});
  EXPECT_TRUE(std::holds_alternative<std::string>(from_compressed_image(std::move(not_jpeg), 0)));
  auto huge = m;
  huge.data().resize(kMaxJpegBytes + 1);
  EXPECT_TRUE(std::holds_alternative<std::string>(from_compressed_image(std::move(huge), 0)));
}

// The payload dds_messages_fuzz found: an encapsulation header Fast CDR does not know (0x07 0x01). The generated
// deserializer throws BadParamException through the DataReader; the type the readers register says no instead.
TEST(DdsMessages, APayloadThatDoesNotDecodeIsRefusedNotThrown) {
  const std::uint8_t bytes[] = {0x00, 0x07, 0x01, 0x00, 0x00, 0x00, 0xd2, 0x49, 0x6b, 0x05, 0x00, 0x00, 0x00, 0x0a,
                                0x00, 0x00, 0x00, 'b',  'a',  's',  'e',  '_',  'l',  'i',  'n',  'k',  0x00, 0x00};
  auto payload = [&] {
    eprosima::fastrtps::rtps::SerializedPayload_t p(sizeof bytes);
    std::memcpy(p.data, bytes, sizeof bytes);
    p.length = sizeof bytes;
    return p;
  };
  fsd_msgs::msg::dds_::ConeDetections_ m;
  auto p1 = payload();
  fsd_msgs::msg::dds_::ConeDetections_PubSubType generated;
  EXPECT_ANY_THROW(generated.deserialize(&p1, &m));  // what Fast DDS's own reader would let escape
  auto p2 = payload();
  CheckedType<fsd_msgs::msg::dds_::ConeDetections_PubSubType> checked;
  bool ok = true;
  EXPECT_NO_THROW(ok = checked.deserialize(&p2, &m));
  EXPECT_FALSE(ok);
}

TEST(DdsMessages, RosTimeSplitsSecondsAndNanoseconds) {
  const RosTime t = to_ros_time(1800000000.9999999999);  // rounds up into the next second
  EXPECT_EQ(t.sec, 1800000001);
  EXPECT_EQ(t.nanosec, 0u);
  const RosTime u = to_ros_time(12.5);
  EXPECT_EQ(u.sec, 12);
  EXPECT_EQ(u.nanosec, 500000000u);
}

}  // namespace
}  // namespace fsd::dds
