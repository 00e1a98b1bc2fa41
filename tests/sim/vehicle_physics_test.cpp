// The virtual car against hand-computed vehicle physics (issue 3, "Done when"). Expectations come from textbook
// formulas evaluated here with the parameters, never from the model's own outputs.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "drivers/sim/vehicle/vehicle_model.hpp"
#include "tests/sim/vehicle_test_helpers.hpp"

namespace fsd::sim {
namespace {

using test::kDt;
using test::kG;

double dynamic_pressure(const VehicleParams& p, double v) { return 0.5 * p.air_density * v * v; }

// ---------------------------------------------------------------------------------------------------------------
// Steady-state cornering

struct CircleRun {
  test::Circle rear_axle_path, cog_path;
  double speed = 0, vx = 0, yaw_rate = 0, ay = 0, sideslip = 0;  // averages over the recording
};

// Drives at a constant target speed and steering command, lets the car settle, then records a stretch.
CircleRun drive_circle(const VehicleParams& p, double speed, double steering, bool start_rolling) {
  VehicleModel car(p);
  car.reset(Pose2{}, start_rolling ? speed : 0.0);
  const ActuatorCommand cmd = test::drive(speed, steering);
  test::run_for(car, cmd, 15.0);
  std::vector<Eigen::Vector2d> rear, cog;
  CircleRun r;
  int n = 0;
  test::run_for(car, cmd, 8.0, [&](const VehicleTruth& t) {
    rear.push_back(t.pose.position());
    cog.push_back(t.pose.transform({p.cog_to_rear_axle, 0.0}));  // the CoG lies on the body's x axis
    r.speed += t.speed();
    r.vx += t.vx;
    r.yaw_rate += t.yaw_rate;
    r.ay += t.ay;
    r.sideslip += t.sideslip();
    ++n;
  });
  r.speed /= n;
  r.vx /= n;
  r.yaw_rate /= n;
  r.ay /= n;
  r.sideslip /= n;
  r.rear_axle_path = test::fit_circle(rear);
  r.cog_path = test::fit_circle(cog);
  return r;
}

TEST(VehiclePhysics, SteadyCircleAtSpeedLateralAccelerationAndNegativeSideslip) {
  const VehicleParams p;
  const CircleRun c = drive_circle(p, 18.0, 0.05, true);
  ASSERT_LT(c.cog_path.rms_residual, 0.02) << "the path is not a steady circle";
  EXPECT_NEAR(c.speed, 18.0, 0.1);

  // The CoG runs on a circle of radius R at speed V: centripetal acceleration V²/R towards the centre. The body
  // is turned by the sideslip β against the velocity, so the lateral accelerometer reads V²/R·cos β.
  const double centripetal = c.speed * c.speed / c.cog_path.radius;
  EXPECT_NEAR(c.ay, centripetal * std::cos(c.sideslip), 0.01 * centripetal);
  // In steady state the lateral acceleration is also forward speed times yaw rate.
  EXPECT_NEAR(c.ay, c.vx * c.yaw_rate, 0.01 * centripetal);
  // And the yaw rate is the angular speed around the circle.
  EXPECT_NEAR(c.yaw_rate, c.speed / c.cog_path.radius, 0.01 * c.yaw_rate);
  EXPECT_GT(c.ay, 5.0);              // a real test of the tyres, ...
  EXPECT_LT(c.ay, p.mu * kG * 1.2);  // ... below what they can give with the downforce

  // Sideslip at the CoG: the rear tyres must run at a slip angle α_r ≈ F_yr / C_r to carry their share of m·v²/R,
  // so the rear axle's velocity points outwards (to the right on this left turn) by α_r. The CoG sits l_r ahead of
  // the rear axle, which turns its velocity inwards by ≈ l_r / R. β ≈ l_r / R − α_r: α_r grows with v²/R while
  // l_r / R does not, so at speed β is negative (the nose points into the turn, ahead of the velocity).
  EXPECT_LT(c.sideslip, -0.002);
  RecordProperty("ay", std::to_string(c.ay));
  RecordProperty("sideslip", std::to_string(c.sideslip));
  RecordProperty("radius", std::to_string(c.cog_path.radius));
}

TEST(VehiclePhysics, SteadyCircleAtLowSpeedHasPositiveSideslip) {
  // At 5 m/s the rear slip angle is small and the geometric term l_r / R dominates: β > 0, a little below the
  // kinematic value atan(l_r / R_rear).
  const VehicleParams p;
  const CircleRun c = drive_circle(p, 5.0, 0.15, true);
  const double kinematic_beta = std::atan(p.cog_to_rear_axle / c.rear_axle_path.radius);
  EXPECT_GT(c.sideslip, 0.5 * kinematic_beta);
  EXPECT_LT(c.sideslip, kinematic_beta);
  const double centripetal = c.speed * c.speed / c.cog_path.radius;
  EXPECT_NEAR(c.ay, centripetal * std::cos(c.sideslip), 0.01 * centripetal);
}

TEST(VehiclePhysics, KinematicRadiusAtWalkingSpeed) {
  // At 1 m/s the tyres need almost no slip: the rear axle turns about the point where the rear axle line and the
  // front wheel's normal meet, radius L / tan δ. Started from standstill through the VCU's speed controller.
  const VehicleParams p;
  const double steering = 0.3;
  const CircleRun c = drive_circle(p, 1.0, steering, false);
  EXPECT_NEAR(c.speed, 1.0, 0.02);
  EXPECT_NEAR(c.rear_axle_path.radius, p.wheelbase / std::tan(steering), 0.005 * p.wheelbase / std::tan(steering));
}

// ---------------------------------------------------------------------------------------------------------------
// Straight-line braking

// Distance to stop from v0 under a deceleration a(v): ∫₀^v0 v / a(v) dv.
double stopping_distance(double v0, const std::function<double(double)>& decel) {
  return test::simpson([&](double v) { return v / decel(v); }, 0.0, v0);
}

// Brakes from v0 on a straight and returns the distance travelled along x until the car stands.
double measured_stop(const VehicleParams& p, double v0, bool ebs) {
  VehicleModel car(p);
  car.reset(Pose2{}, v0);
  ActuatorCommand cmd;
  cmd.drive_enabled = true;
  cmd.target_speed = v0;
  (ebs ? cmd.ebs : cmd.max_brake) = true;
  for (int i = 0; i < 5000 && car.truth().vx > 0.0; ++i) car.step(kDt, cmd);
  EXPECT_EQ(car.truth().vx, 0.0);
  EXPECT_NEAR(car.truth().pose.y, 0.0, 1e-9);
  EXPECT_NEAR(car.truth().distance, car.truth().pose.x, 1e-3);
  return car.truth().pose.x;
}

TEST(VehiclePhysics, TyreLimitedStopIsNearMuGAndMatchesTheDecelerationIntegral) {
  const VehicleParams p;
  const double v0 = 12.0;
  // The brakes can do more than the tyres: at every speed up to v0 both axles sit at their friction limit, so
  // the tyres give μ times the total normal load (weight plus downforce, however it is split front to rear).
  ASSERT_GT(p.brake_max_force * (1 - p.brake_front_share),
            p.mu * p.mass * kG * (p.cog_to_front_axle() - p.mu * p.cog_height) / p.wheelbase);
  auto decel = [&](double v) {
    const double q = dynamic_pressure(p, v);
    return (p.mu * (p.mass * kG + q * p.downforce_area) + q * p.drag_area + p.rolling_resistance * p.mass * kG) /
           p.mass;
  };
  const double expected = stopping_distance(v0, decel);
  const double textbook = v0 * v0 / (2 * p.mu * kG);  // μg alone, no aero, no rolling resistance
  for (bool ebs : {false, true}) {
    const double d = measured_stop(p, v0, ebs);
    EXPECT_NEAR(d, expected, 0.02 * expected) << (ebs ? "ebs" : "max_brake");
    // Downforce, drag and rolling resistance only shorten it, by a few per cent from 12 m/s.
    EXPECT_LT(d, textbook);
    EXPECT_GT(d, 0.9 * textbook);
  }
}

TEST(VehiclePhysics, BrakeLimitedStopMatchesTheBrakeForce) {
  VehicleParams p;
  p.brake_max_force = 1500.0;  // weak brakes: no axle reaches its friction limit
  const double v0 = 15.0;
  auto decel = [&](double v) {
    const double q = dynamic_pressure(p, v);
    return (p.brake_max_force + q * p.drag_area + p.rolling_resistance * p.mass * kG) / p.mass;
  };
  const double expected = stopping_distance(v0, decel);
  EXPECT_NEAR(measured_stop(p, v0, false), expected, 0.01 * expected);
}

// ---------------------------------------------------------------------------------------------------------------
// Top speed and acceleration

// Largest drive force the motor gives at v, as the parameters state it: torque limit, power limit after the
// drivetrain, and the speed limit's fade over its last 1 m/s.
double motor_force(const VehicleParams& p, double v) {
  const double torque = p.motor_max_torque / p.wheel_radius;
  const double power = p.drivetrain_efficiency * p.motor_max_power / std::max(v, 0.1);
  return std::min(torque, power) * std::clamp(p.max_speed - v, 0.0, 1.0);
}

double resistance(const VehicleParams& p, double v) {
  return dynamic_pressure(p, v) * p.drag_area + p.rolling_resistance * p.mass * kG;
}

double measured_top_speed(const VehicleParams& p) {
  VehicleModel car(p);
  car.reset(Pose2{});
  test::run_for(car, test::drive(p.max_speed), 90.0);
  return car.truth().vx;
}

struct TopSpeedCase {
  const char* name;
  double max_speed, max_torque;
};

class TopSpeed : public ::testing::TestWithParam<TopSpeedCase> {};

TEST_P(TopSpeed, IsWhereTheMotorLimitMeetsDragAndRollingResistance) {
  VehicleParams p;
  p.max_speed = GetParam().max_speed;
  p.motor_max_torque = GetParam().max_torque;
  // Without the speed limit: where min(torque, power) force equals drag + rolling resistance.
  const double unlimited = test::bisect(
      [&](double v) {
        return std::min(p.motor_max_torque / p.wheel_radius, p.drivetrain_efficiency * p.motor_max_power / v) -
               resistance(p, v);
      },
      1.0, 200.0);
  const double measured = measured_top_speed(p);
  if (unlimited < p.max_speed - 1.0) {
    EXPECT_NEAR(measured, unlimited, 0.005 * unlimited);
  } else {
    // The motor speed limit binds: the car settles inside the fade band below max_speed.
    EXPECT_LE(measured, p.max_speed);
    EXPECT_GE(measured, p.max_speed - 1.0);
  }
  RecordProperty("top_speed", std::to_string(measured));
}

INSTANTIATE_TEST_SUITE_P(VehiclePhysics, TopSpeed,
                         ::testing::Values(TopSpeedCase{"speed_limited_default", 32.0, 700.0},
                                           TopSpeedCase{"power_limited", 60.0, 700.0},
                                           TopSpeedCase{"torque_limited", 60.0, 200.0}),
                         [](const auto& info) { return std::string(info.param.name); });

TEST(VehiclePhysics, ZeroTo100IsBoundedByTractionTorqueAndPower) {
  const VehicleParams p;
  const double v_end = 100.0 / 3.6;
  ASSERT_LT(v_end, p.max_speed - 1.0);
  // Fastest possible run: at every speed the drive force is the smallest of the motor's limits and the rear
  // tyres' grip μ·F_zr, where F_zr includes the rear share of the downforce and the load transfer m·a·h/L of
  // the acceleration itself (a = (F − resistance)/m), i.e. F = μ(m g l_f/L + F_down,r − R h/L) / (1 − μ h/L).
  auto accel = [&](double v) {
    const double down_rear = (1 - p.aero_front_share) * dynamic_pressure(p, v) * p.downforce_area;
    const double h_over_l = p.cog_height / p.wheelbase;
    const double grip = p.mu *
                        (p.mass * kG * p.cog_to_front_axle() / p.wheelbase + down_rear - resistance(p, v) * h_over_l) /
                        (1 - p.mu * h_over_l);
    return (std::min(motor_force(p, v), grip) - resistance(p, v)) / p.mass;
  };
  const double bound = test::simpson([&](double v) { return 1.0 / accel(v); }, 0.0, v_end);

  VehicleModel car(p);
  car.reset(Pose2{});
  double t = 0;
  while (car.truth().vx < v_end && t < 20.0) {
    car.step(kDt, test::drive(p.max_speed));
    t += kDt;
  }
  // The model's load transfer lags the acceleration, so it can only be slower than the bound; traction control
  // keeps it close.
  EXPECT_GE(t, bound - kDt);
  EXPECT_LE(t, 1.1 * bound);
  RecordProperty("zero_to_100_s", std::to_string(t));
  RecordProperty("bound_s", std::to_string(bound));
}

// ---------------------------------------------------------------------------------------------------------------
// Coast-down

TEST(VehiclePhysics, CoastDownDecelerationIsDragPlusRollingResistance) {
  const VehicleParams p;
  VehicleModel car(p);
  car.reset(Pose2{}, 25.0);
  ActuatorCommand coast;  // drive disabled, no brake
  std::vector<double> v;
  test::run_for(car, coast, 80.0, [&](const VehicleTruth& t) { v.push_back(t.vx); });
  for (double vc : {22.0, 15.0, 8.0, 2.5, 1.0}) {
    const auto it = std::find_if(v.begin(), v.end(), [&](double x) { return x < vc; });
    ASSERT_NE(it, v.end()) << "never slowed below " << vc;
    const auto i = static_cast<std::size_t>(it - v.begin());
    const std::size_t k = 10;
    ASSERT_GT(i, k);
    ASSERT_LT(i + k, v.size());
    const double measured = (v[i - k] - v[i + k]) / (2 * k * kDt);
    const double expected = resistance(p, vc) / p.mass;
    EXPECT_NEAR(measured, expected, 0.01 * expected) << "at " << vc << " m/s";
  }
  // It rolls to a stop on rolling resistance and stays there.
  EXPECT_EQ(v.back(), 0.0);
}

}  // namespace
}  // namespace fsd::sim
