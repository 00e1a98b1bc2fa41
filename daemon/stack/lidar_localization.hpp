#pragma once
// The LiDAR odometry's side on the control thread: each VLP-16 scan goes through the LOAM-style odometry
// (localization/lidar_odometry), integrated from the start pose (localization.start: where the car stands at the
// start, in the map frame; the map frame's origin by default, DESIGN.md §5). With
// localization.lidar_odometry.vehicle_motion the car's own motion sensors (the rear wheels' speed, the GNSS-INS
// unit's yaw rate: never its position) deskew and predict each scan, as LOAM's IMU-aided mode does.
//
// The odometry's scan match itself runs on the Stack's processing thread (ScanProcessor, made by make_odometry),
// which takes each scan with the twist measured over it (motion_over) and hands the output back (accept); its
// increments go into the fusion filter (FusedLocalization), with the satellites (the fused source) or without
// them (the lidar_odometry source).
#include <deque>
#include <memory>
#include <optional>

#include "common/config.hpp"
#include "common/types.hpp"
#include "localization/lidar_odometry/lidar_odometry.hpp"

namespace fsd {

// localization.start: the body's pose at the start in the map frame.
struct StartPose {
  double x = 0, y = 0, yaw = 0;
  Pose2 pose() const { return {x, y, yaw}; }
};
const ConfigSection<StartPose>& start_pose_section();

struct LidarLocalizationMotion {
  Stamp t;
  double value;
};

// The odometry's scan matcher, started at localization.start; `body_from_sensor`: the LiDAR's mount (car.lidar.*).
std::unique_ptr<lidar_odometry::LidarOdometry> make_odometry(const Config& cfg, const Pose3& body_from_sensor);

class LidarLocalization {
 public:
  explicit LidarLocalization(const Config& cfg);
  // Whether the odometry takes this scan: one with points, newer than the last it took (in time order).
  bool takes(const Scan& scan) const;
  // The car's measured twist over a scan's firings, for the odometry's deskew and prediction; empty without
  // localization.lidar_odometry.vehicle_motion or without recent measurements.
  std::optional<lidar_odometry::Vec6> motion_over(const Scan& scan) const;
  // The odometry's output for the scan it took last.
  void accept(const lidar_odometry::OdometryOutput& out);
  // The car's measured motion: the rear axle's forward speed and the yaw rate (either may be absent), by stamp.
  void add_motion(Stamp t, std::optional<double> speed, std::optional<double> yaw_rate);
  // The newest scan's increment, if it had one (the first scan has none).
  std::optional<fusion::OdometryIncrement> increment() const;

 private:
  // The measured twist over the span of a scan, when the car's sensors gave it recently enough.
  std::optional<lidar_odometry::Vec6> measured(Stamp from, Stamp to) const;

  bool vehicle_motion_ = true;
  std::deque<LidarLocalizationMotion> speeds_, yaw_rates_;  // the last second of each, bounded
  lidar_odometry::OdometryOutput last_;
  bool have_ = false;
};

}  // namespace fsd
