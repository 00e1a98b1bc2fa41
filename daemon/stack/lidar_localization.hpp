#pragma once
// run.localization_source = lidar_odometry: the pose from the LiDAR alone. Each VLP-16 scan goes through the
// LOAM-style odometry (localization/lidar_odometry), integrated from the start pose (localization.start.*: where
// the car stands at the start, in the map frame; the map frame's origin by default, DESIGN.md §5). The odometry
// gives a pose at each scan's last firing (10 Hz). With localization.lidar_odometry.vehicle_motion the car's own
// motion sensors (the rear wheels' speed, the GNSS-INS unit's yaw rate: never its position) deskew and predict
// each scan, as LOAM's IMU-aided mode does, and carry the pose from the scan to each control cycle; without them,
// the newest increment's motion carries it.
//
// This is the control thread's side: the motion measurements, the newest scan's output, the loop closures'
// correction. The odometry's scan match itself runs on the Stack's processing thread (ScanProcessor, made by
// make_odometry), which takes each scan with the twist measured over it (motion_over) and hands the output back
// (accept).
//
// The fused source uses the same odometry for its increments (localization.fusion.lidar_odometry).
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
  // The state at `now`, carried forward from the newest scan's pose with the odometry's twist; empty before the
  // first scan. `steering`: the VCU's measured steering angle (not the LiDAR's to know).
  std::optional<VehicleState> state(Stamp now, double steering) const;
  // A loop closure: the odometry's poses are off by `map_from_estimate` (map ← the pose as state() gave it); state()
  // gives corrected poses from now on. The odometry itself and its increments stay as they are (output(): raw).
  void correct(const Pose2& map_from_estimate) { map_from_odometry_ = map_from_estimate * map_from_odometry_; }
  const Pose2& map_from_odometry() const { return map_from_odometry_; }
  // The newest scan's increment, if it had one (the first scan has none).
  std::optional<fusion::OdometryIncrement> increment() const;

 private:
  // The measured twist over the span of a scan, when the car's sensors gave it recently enough.
  std::optional<lidar_odometry::Vec6> measured(Stamp from, Stamp to) const;

  bool vehicle_motion_ = true;
  std::deque<LidarLocalizationMotion> speeds_, yaw_rates_;  // the last second of each, bounded
  lidar_odometry::OdometryOutput last_;
  bool have_ = false;
  Pose2 map_from_odometry_;  // the loop closures' corrections so far
};

}  // namespace fsd
