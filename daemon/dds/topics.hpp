#pragma once
// The ROS 2 names of the daemon's topics (docs/dds.md). On the wire each is "rt" + the name.
namespace fsd::dds {

inline constexpr const char* kCloudTopic = "/fsd/lidar/points";                // sensor_msgs/PointCloud2
inline constexpr const char* kDetectionsTopic = "/fsd/perception/detections";  // fsd_msgs/ConeDetections
inline constexpr const char* kPerceptionConesTopic = "/fsd/perception/cones";  // eufs_msgs/ConeArrayWithCovariance
inline constexpr const char* kPerceptionMarkersTopic =
    "/fsd/perception/cone_markers";                                          // visualization_msgs/MarkerArray
inline constexpr const char* kMapConesTopic = "/fsd/map/cones";              // eufs_msgs/ConeArrayWithCovariance
inline constexpr const char* kMapMarkersTopic = "/fsd/map/cone_markers";     // visualization_msgs/MarkerArray
inline constexpr const char* kOdomTopic = "/fsd/odom";                       // nav_msgs/Odometry
inline constexpr const char* kCommandTopic = "/fsd/control/command";         // ackermann_msgs/AckermannDriveStamped
inline constexpr const char* kStatusTopic = "/fsd/as/status";                // fsd_msgs/AsStatus
inline constexpr const char* kLapsTopic = "/fsd/laps";                       // fsd_msgs/LapEvent
inline constexpr const char* kFaultsTopic = "/fsd/faults";                   // fsd_msgs/Fault
inline constexpr const char* kCameraTopic = "/fsd/camera/image/compressed";  // sensor_msgs/CompressedImage

}  // namespace fsd::dds
