// Split mode's inputs from the network (docs/dds.md): the CDR payload of a DDS sample as Fast DDS hands it to the
// type's deserializer, then the daemon's check of the decoded message (daemon/dds/ros_messages.cpp). The first byte
// picks the topic: the perception frame the driving daemon takes (fsd_msgs/ConeDetections), the pose and the
// camera frame the perception process takes (nav_msgs/Odometry, sensor_msgs/CompressedImage).
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <variant>

#include <fastdds/rtps/common/SerializedPayload.h>

#include "daemon/dds/checked_type.hpp"
#include "daemon/dds/ros_messages.hpp"
#include "fsd_msgs/msg/ConeDetectionsPubSubTypes.h"
#include "nav_msgs/msg/OdometryPubSubTypes.h"
#include "sensor_msgs/msg/CompressedImagePubSubTypes.h"

namespace {

// The payload as the wire carries it (encapsulation header, then the data), in a buffer of its own size.
eprosima::fastrtps::rtps::SerializedPayload_t payload(const std::uint8_t* data, std::size_t size) {
  eprosima::fastrtps::rtps::SerializedPayload_t p(static_cast<std::uint32_t>(size));
  if (size) std::memcpy(p.data, data, size);
  p.length = static_cast<std::uint32_t>(size);
  return p;
}

// The type as the daemon's readers register it (daemon/dds/checked_type.hpp).
template <class Generated, class Msg, class Check>
void one(const std::uint8_t* data, std::size_t size, Check check) {
  fsd::dds::CheckedType<Generated> type;
  Msg m;
  auto p = payload(data, size);
  if (!type.deserialize(&p, &m)) return;
  auto checked = check(std::move(m));
  // A value that passed the check is whole: its numbers are finite (the sanitizers see any use of garbage).
  if (auto* v = std::get_if<0>(&checked)) (void)v;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  const std::uint8_t which = data[0] % 3;
  ++data;
  --size;
  constexpr double epoch = 1.8e9;
  using namespace fsd::dds;
  switch (which) {
    case 0:
      one<fsd_msgs::msg::dds_::ConeDetections_PubSubType, fsd_msgs::msg::dds_::ConeDetections_>(
          data, size, [](fsd_msgs::msg::dds_::ConeDetections_&& m) { return from_detections(m, epoch); });
      break;
    case 1:
      one<nav_msgs::msg::dds_::Odometry_PubSubType, nav_msgs::msg::dds_::Odometry_>(
          data, size, [](nav_msgs::msg::dds_::Odometry_&& m) { return from_odometry(m, epoch); });
      break;
    default:
      one<sensor_msgs::msg::dds_::CompressedImage_PubSubType, sensor_msgs::msg::dds_::CompressedImage_>(
          data, size,
          [](sensor_msgs::msg::dds_::CompressedImage_&& m) { return from_compressed_image(std::move(m), epoch); });
      break;
  }
  return 0;
}
