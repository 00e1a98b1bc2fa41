// The lateral acceleration the dashboard plots, from the sources that do not measure it (GNSS-INS alone, the fused
// filter): on a steady circle it must be the circle's centripetal acceleration v²/R.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "common/config.hpp"
#include "daemon/stack/fused_localization.hpp"
#include "daemon/stack/gnss_state.hpp"
#include "daemon/stack/settings.hpp"

namespace fsd {
namespace {

constexpr double kSpeed = 10.0, kRadius = 20.0;  // v²/R = 5 m/s²

// The rear axle on a counter-clockwise circle about the origin at time t, as an RTK receiver with a dual-antenna
// heading reports it (50 Hz).
GnssSample on_circle(double t) {
  const double w = kSpeed / kRadius, a = w * t;
  GnssSample s;
  s.stamp = t;
  s.enu = Vec3(kRadius * std::cos(a), kRadius * std::sin(a), 0.0);
  s.heading = s.course = a + M_PI / 2;
  s.speed = kSpeed;
  s.yaw_rate = w;
  s.velocity_valid = s.yaw_rate_valid = s.heading_valid = true;
  s.fix_quality = 4;
  s.satellites = 14;
  s.hdop = 0.7;
  s.good = true;
  return s;
}

TEST(VehicleState, GnssAloneGivesTheCirclesCentripetalAcceleration) {
  const VehicleState v = state_from_gnss(on_circle(3.0), 0.0);
  EXPECT_NEAR(v.ay, kSpeed * kSpeed / kRadius, 1e-9);
}

TEST(VehicleState, TheFusedFilterGivesTheCirclesCentripetalAcceleration) {
  const Config cfg(config_schema());
  FusedLocalization fused(cfg);
  for (int k = 0; k <= 500; ++k) {  // 10 s at 50 Hz, the rear wheels at the circle's speed
    const double t = 0.02 * k;
    VcuStatus vcu;
    vcu.stamp = t;
    vcu.wheel_speeds = {kSpeed, kSpeed, kSpeed, kSpeed};
    fused.add({on_circle(t)}, vcu);
  }
  const auto v = fused.state(0.0);
  ASSERT_TRUE(v.has_value());
  EXPECT_NEAR(v->ay, kSpeed * kSpeed / kRadius, 0.25);
}

}  // namespace
}  // namespace fsd
