#pragma once
// The stack's types as ROS 2 messages (the types fastddsgen generates from idl/), both ways. Outgoing: the cloud,
// detections and cone map (three forms), odometry, the command, the AS status, laps, faults. Incoming, in split
// mode, from the network and so untrusted: the perception frame (fsd_msgs/ConeDetections), the odometry the
// perception process places scans by, the camera's JPEG frames. Each incoming message is checked whole (finite
// numbers in range, bounded counts, known enum values) and refused with the reason, never half used.
#include <cstdint>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "ackermann_msgs/msg/AckermannDriveStamped.h"
#include "common/types.hpp"
#include "daemon/dds/ros_time.hpp"
#include "eufs_msgs/msg/ConeArrayWithCovariance.h"
#include "fsd_msgs/msg/ConeDetections.h"
#include "fsd_msgs/msg/Status.h"
#include "nav_msgs/msg/Odometry.h"
#include "sensor_msgs/msg/CompressedImage.h"
#include "sensor_msgs/msg/PointCloud2.h"
#include "visualization_msgs/msg/MarkerArray.h"

namespace fsd::dds {

// Frame ids, as ROS (REP-105) names them: the map, the car's body (rear-axle centre), the LiDAR.
inline constexpr const char* kMapFrame = "map";
inline constexpr const char* kBodyFrame = "base_link";
inline constexpr const char* kLidarFrame = "lidar";

// Bounds on what split mode accepts (a VLP-16 scan sees well under 1000 cone candidates; a camera JPEG is < 1 MB).
inline constexpr std::size_t kMaxRemoteCones = 1000;
inline constexpr std::size_t kMaxJpegBytes = 4 << 20;
inline constexpr double kMaxCoordinate = 1e5;  // m: farther than any track from its start

// Outgoing. `epoch`: the epoch time of the run clock's zero (ros_time.hpp).
sensor_msgs::msg::dds_::PointCloud2_ to_point_cloud(const Scan& scan, double epoch);
fsd_msgs::msg::dds_::ConeDetections_ to_detections(const ConeDetections& d, const std::vector<Cone>& camera_rejected,
                                                   double epoch);
eufs_msgs::msg::dds_::ConeArrayWithCovariance_ to_cone_array(const std::vector<Cone>& cones, Stamp t, const char* frame,
                                                             double epoch);
visualization_msgs::msg::dds_::MarkerArray_ to_markers(const std::vector<Cone>& cones, Stamp t, const char* frame,
                                                       const std::string& ns, double epoch);
nav_msgs::msg::dds_::Odometry_ to_odometry(const VehicleState& s, double epoch);
ackermann_msgs::msg::dds_::AckermannDriveStamped_ to_drive(const ControlCommand& c, double epoch);
sensor_msgs::msg::dds_::CompressedImage_ to_compressed_image(const std::vector<std::uint8_t>& jpeg, Stamp capture,
                                                             double epoch);

// Incoming: the value, or why it was refused. Stamps come back on this process's run clock (`epoch` its zero).
template <class T>
using Checked = std::variant<T, std::string>;

struct RemoteDetections {
  ConeDetections detections;          // vehicle frame, stamped at the scan
  std::vector<Cone> camera_rejected;  // what the camera stage removed (the cone map's negative evidence)
};
Checked<RemoteDetections> from_detections(const fsd_msgs::msg::dds_::ConeDetections_& m, double epoch);

struct RemotePose {
  Stamp t = 0;
  Pose2 pose;  // map frame
};
Checked<RemotePose> from_odometry(const nav_msgs::msg::dds_::Odometry_& m, double epoch);

struct RemoteImage {
  Stamp capture = 0;
  std::vector<std::uint8_t> jpeg;
};
Checked<RemoteImage> from_compressed_image(sensor_msgs::msg::dds_::CompressedImage_&& m, double epoch);

}  // namespace fsd::dds
