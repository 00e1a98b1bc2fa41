#include "daemon/lidar_localization.hpp"

#include <cmath>

namespace fsd {

const ConfigSection<StartPose>& start_pose_section() {
  static const auto s =
      ConfigSection<StartPose>("localization.start")
          .number("x", &StartPose::x, -1e6, 1e6, "m",
                  "Where the rear-axle centre stands at the start, in the map frame (the LiDAR odometry's origin). "
                  "The virtual car sets the track's car_start.")
          .number("y", &StartPose::y, -1e6, 1e6, "m", "... its y.")
          .number("yaw", &StartPose::yaw, -3.15, 3.15, "rad", "... and the car's heading there.");
  return s;
}

LidarLocalization::LidarLocalization(const Config& cfg, const Pose3& body_from_sensor)
    : odometry_(lidar_odometry::read_lidar_odometry_config(cfg), body_from_sensor) {
  // The car stands at the start: a standing first prediction is right.
  odometry_.start_at(start_pose_section().read(cfg).pose().to_pose3());
}

const lidar_odometry::OdometryOutput& LidarLocalization::add(const Scan& scan) {
  if (scan.points.empty() || (have_ && firing_span(scan).last <= last_.stamp)) return last_;
  last_ = odometry_.process(scan);
  have_ = true;
  ++scans_;
  degenerate_ += last_.diagnostics.degenerate;
  return last_;
}

std::optional<VehicleState> LidarLocalization::state(Stamp now, double steering) const {
  if (!have_) return std::nullopt;
  // The newest increment's own motion (the odometry's low-passed twist lags braking and turn-in by half a second),
  // carried on from the scan's last firing to now: at most a scan period, ~0.8 m at 8 m/s.
  double vx = 0, vy = 0, r = 0;
  if (last_.has_increment) {
    const auto& inc = last_.increment;
    const double dt = inc.t1 - inc.t0;
    const Vec2 chord = Eigen::Rotation2Dd(-0.5 * inc.delta.yaw) * Vec2(inc.delta.x, inc.delta.y);
    vx = chord.x() / dt;
    vy = chord.y() / dt;
    r = inc.delta.yaw / dt;
  }
  const double ahead = std::max(0.0, now - last_.stamp);
  const Pose2 at_scan = to_pose2(last_.pose);
  const double half = 0.5 * r * ahead;  // along the chord of the arc
  const Vec2 step = Eigen::Rotation2Dd(half) * Vec2(vx * ahead, vy * ahead);
  VehicleState s;
  s.stamp = std::max(now, last_.stamp);
  s.pose = at_scan * Pose2{step.x(), step.y(), r * ahead};
  s.vx = vx;
  s.vy = vy;
  s.yaw_rate = r;
  s.steering = std::isfinite(steering) ? steering : 0.0;
  return s;
}

std::optional<fusion::OdometryIncrement> LidarLocalization::increment() const {
  if (!have_ || !last_.has_increment) return std::nullopt;
  return last_.increment;
}

}  // namespace fsd
