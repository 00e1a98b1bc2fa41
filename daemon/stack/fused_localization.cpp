#include "daemon/stack/fused_localization.hpp"

#include <algorithm>
#include <cmath>

#include "common/car.hpp"
#include "daemon/stack/lidar_localization.hpp"

namespace fsd {

namespace {
// How well the start pose is known without satellites: it is the map frame's definition, so only the staging's
// error counts (a car placed on the start line by hand: a centimetre, a tenth of a degree).
constexpr double kStartSigma = 0.01;      // m
constexpr double kStartYawSigma = 0.002;  // rad
}  // namespace

FusedLocalization::FusedLocalization(const Config& cfg, Satellites satellites) : satellites_(satellites) {
  const auto fc = fusion::read_fusion_config(cfg);
  filter_ = fusion::make_fusion_filter(fc.common.filter, fc);
  lidar_odometry_ = fc.common.lidar_odometry || satellites == Satellites::Denied;
  if (satellites == Satellites::Denied)
    filter_->start_at(start_pose_section().read(cfg).pose(), kStartSigma, kStartYawSigma);
  good_gnss_timeout_ = fc.common.good_gnss_timeout_s;
  wheelbase_ = read_car(cfg).wheelbase;
}

bool FusedLocalization::gnss_recent() const {
  const auto e = filter_->state();
  return e.last_gnss_accepted >= 0 && e.stamp - e.last_gnss_accepted <= good_gnss_timeout_;
}

std::optional<Pose2> FusedLocalization::add_map_correction(const Pose2& correction, double sigma, double yaw_sigma) {
  const auto e = filter_->state();
  if (!e.initialised) return std::nullopt;
  filter_->add(fusion::MapPose{e.stamp, correction * e.pose, sigma, yaw_sigma});
  const auto after = filter_->state();
  if (after.last_map_pose != e.stamp) return std::nullopt;
  return after.pose * e.pose.inverse();
}

void FusedLocalization::add(const std::vector<GnssSample>& gnss, const std::optional<VcuStatus>& vcu,
                            const std::optional<fusion::OdometryIncrement>& odometry) {
  std::vector<fusion::Measurement> ms;
  // A scan is complete only when the next one's first packet arrives and is processed after: its increment is
  // older than what the filter has taken, and the filter takes it as the motion at its own time.
  if (odometry && lidar_odometry_) ms.emplace_back(*odometry);
  for (const auto& s : gnss) {
    if (s.yaw_rate_valid && std::isfinite(s.yaw_rate))
      ms.emplace_back(fusion::ImuSample{s.stamp, Vec3(0, 0, s.yaw_rate), Vec3::Zero()});
    if (satellites_ == Satellites::Denied) continue;
    fusion::GnssFix f;
    f.t = s.stamp;
    f.position = s.enu.head<2>();
    f.fix_quality = s.fix_quality;
    f.age_s = s.age_s;
    f.heading_valid = s.heading_valid;
    f.heading = s.heading;
    f.heading_sigma = s.heading_sigma;
    // Speed and course: the velocity over ground (a course is only given when moving).
    f.velocity_valid = s.velocity_valid && s.speed > 0.5 && std::isfinite(s.speed) && std::isfinite(s.course);
    if (f.velocity_valid) f.velocity = s.speed * Vec2(std::cos(s.course), std::sin(s.course));
    ms.emplace_back(f);
  }
  if (vcu && vcu->stamp > last_vcu_) {
    last_vcu_ = vcu->stamp;
    fusion::BodySpeed b;
    b.t = vcu->stamp;
    b.source = fusion::BodySpeed::Source::Wheels;
    b.vx = vcu->rear_axle_speed();  // the reference point's speed
    b.has_vy = false;
    if (wheelbase_ > 0 && std::isfinite(vcu->steering_measured))
      b.kinematic_yaw_rate = b.vx * kinematic_curvature(vcu->steering_measured, wheelbase_);
    ms.emplace_back(b);
  }
  std::stable_sort(ms.begin(), ms.end(), [](const fusion::Measurement& a, const fusion::Measurement& b) {
    return fusion::stamp_of(a) < fusion::stamp_of(b);
  });
  for (const auto& m : ms) filter_->add(m);
}

std::optional<VehicleState> FusedLocalization::state(double steering_measured) const {
  const auto e = filter_->state();
  if (!e.initialised) return std::nullopt;
  VehicleState v;
  v.stamp = e.stamp;
  v.pose = e.pose;
  v.vx = e.vx;
  v.vy = e.vy;
  v.yaw_rate = e.yaw_rate;
  v.ay = v.kinematic_ay();
  v.steering = std::isfinite(steering_measured) ? steering_measured : 0.0;
  return v;
}

}  // namespace fsd
