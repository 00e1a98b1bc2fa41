#include "daemon/stack/gnss_state.hpp"

#include <cmath>

namespace fsd {

bool gnss_pose_usable(const GnssSample& s, bool have_origin) {
  return have_origin && s.fix_quality != 0 && s.heading_valid && std::isfinite(s.enu.x()) && std::isfinite(s.enu.y()) &&
         std::isfinite(s.heading);
}

VehicleState state_from_gnss(const GnssSample& s, double steering_measured) {
  VehicleState v;
  v.stamp = s.stamp;
  v.pose = Pose2{s.enu.x(), s.enu.y(), s.heading};
  if (s.velocity_valid && std::isfinite(s.speed)) {
    // Course is the direction of travel, heading where the car points: their difference is the sideslip.
    const double beta = s.course - s.heading;
    v.vx = s.speed * std::cos(beta);
    v.vy = s.speed * std::sin(beta);
  }
  if (s.yaw_rate_valid && std::isfinite(s.yaw_rate)) v.yaw_rate = s.yaw_rate;
  v.ay = v.kinematic_ay();
  v.steering = std::isfinite(steering_measured) ? steering_measured : 0.0;
  return v;
}

}  // namespace fsd
