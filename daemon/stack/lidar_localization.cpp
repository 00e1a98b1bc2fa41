#include "daemon/stack/lidar_localization.hpp"

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

namespace {
constexpr double kMotionKept = 1.0;   // s of wheel speeds and yaw rates kept
constexpr double kMotionStale = 0.1;  // s: a measurement older than this at the scan's end is not the car's motion
constexpr std::size_t kMotionMax = 1024;

void keep(std::deque<LidarLocalizationMotion>& q, Stamp t, double v) {
  if (!std::isfinite(v) || (!q.empty() && t < q.back().t)) return;
  q.push_back({t, v});
  while (q.size() > kMotionMax || (q.size() > 1 && q.front().t < t - kMotionKept)) q.pop_front();
}

// The mean over [from, to] of a measurement held between samples; empty when none is recent enough.
std::optional<double> mean_over(const std::deque<LidarLocalizationMotion>& q, Stamp from, Stamp to) {
  if (q.empty() || q.back().t < to - kMotionStale) return std::nullopt;
  double sum = 0;
  int n = 0;
  for (const auto& m : q)
    if (m.t >= from - kMotionStale && m.t <= to + kMotionStale) sum += m.value, ++n;
  if (n == 0) return q.back().value;
  return sum / n;
}
}  // namespace

std::unique_ptr<lidar_odometry::LidarOdometry> make_odometry(const Config& cfg, const Pose3& body_from_sensor) {
  auto odometry = std::make_unique<lidar_odometry::LidarOdometry>(lidar_odometry::read_lidar_odometry_config(cfg),
                                                                  body_from_sensor);
  // The car stands at the start: a standing first prediction is right.
  odometry->start_at(start_pose_section().read(cfg).pose().to_pose3());
  return odometry;
}

LidarLocalization::LidarLocalization(const Config& cfg)
    : vehicle_motion_(lidar_odometry::odometry_section().read(cfg).vehicle_motion) {}

bool LidarLocalization::takes(const Scan& scan) const {
  return !scan.points.empty() && (!have_ || firing_span(scan).last > last_.stamp);
}

std::optional<lidar_odometry::Vec6> LidarLocalization::motion_over(const Scan& scan) const {
  const FiringSpan span = firing_span(scan);
  return measured(span.first, span.last);
}

void LidarLocalization::accept(const lidar_odometry::OdometryOutput& out) {
  last_ = out;
  have_ = true;
}

void LidarLocalization::add_motion(Stamp t, std::optional<double> speed, std::optional<double> yaw_rate) {
  if (!vehicle_motion_) return;
  if (speed) keep(speeds_, t, *speed);
  if (yaw_rate) keep(yaw_rates_, t, *yaw_rate);
}

std::optional<lidar_odometry::Vec6> LidarLocalization::measured(Stamp from, Stamp to) const {
  if (!vehicle_motion_) return std::nullopt;
  const auto v = mean_over(speeds_, from, to), r = mean_over(yaw_rates_, from, to);
  if (!v || !r) return std::nullopt;
  lidar_odometry::Vec6 twist = lidar_odometry::Vec6::Zero();
  twist[0] = *v;
  twist[5] = *r;
  return twist;
}

std::optional<fusion::OdometryIncrement> LidarLocalization::increment() const {
  if (!have_ || !last_.has_increment) return std::nullopt;
  return last_.increment;
}

}  // namespace fsd
