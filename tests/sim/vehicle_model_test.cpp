// Behaviour of the virtual car's vehicle model beyond the physics benchmarks: actuators, the VCU's speed
// controller, standstill, determinism, reset, outputs and parameter handling.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

#include <nlohmann/json.hpp>

#include "drivers/sim/vehicle/vehicle_model.hpp"
#include "tests/sim/vehicle_test_helpers.hpp"

namespace fsd::sim {
namespace {

using test::kDt;

bool all_finite(const VehicleTruth& t) {
  const double v[] = {t.t,
                      t.pose.x,
                      t.pose.y,
                      t.pose.yaw,
                      t.vx,
                      t.vy,
                      t.yaw_rate,
                      t.ax,
                      t.ay,
                      t.roll,
                      t.pitch,
                      t.steering,
                      t.wheel_speeds[0],
                      t.wheel_speeds[1],
                      t.wheel_speeds[2],
                      t.wheel_speeds[3],
                      t.motor_torque,
                      t.brake_force,
                      t.distance};
  for (double x : v)
    if (!std::isfinite(x)) return false;
  return true;
}

void expect_same(const VehicleTruth& a, const VehicleTruth& b) {
  EXPECT_EQ(a.t, b.t);
  EXPECT_EQ(a.pose.x, b.pose.x);
  EXPECT_EQ(a.pose.y, b.pose.y);
  EXPECT_EQ(a.pose.yaw, b.pose.yaw);
  EXPECT_EQ(a.vx, b.vx);
  EXPECT_EQ(a.vy, b.vy);
  EXPECT_EQ(a.yaw_rate, b.yaw_rate);
  EXPECT_EQ(a.ax, b.ax);
  EXPECT_EQ(a.ay, b.ay);
  EXPECT_EQ(a.roll, b.roll);
  EXPECT_EQ(a.pitch, b.pitch);
  EXPECT_EQ(a.steering, b.steering);
  EXPECT_EQ(a.wheel_speeds, b.wheel_speeds);
  EXPECT_EQ(a.motor_torque, b.motor_torque);
  EXPECT_EQ(a.brake_force, b.brake_force);
  EXPECT_EQ(a.distance, b.distance);
}

// A varied drive: launch, slalom, a hard stop, a restart; command i of a fixed script.
ActuatorCommand scripted(int i) {
  const double t = i * kDt;
  ActuatorCommand c = test::drive(t < 12 ? 12.0 : 6.0, 0.25 * std::sin(1.3 * t));
  c.max_brake = t > 8 && t < 10;
  return c;
}

TEST(VehicleModel, SameInputsGiveIdenticalTruth) {
  const VehicleParams p;
  VehicleModel a(p), b(p);
  const Pose2 start{3.0, -2.0, 0.7};
  a.reset(start);
  b.reset(start);
  for (int i = 0; i < 3000; ++i) {
    a.step(kDt, scripted(i));
    b.step(kDt, scripted(i));
  }
  expect_same(a.truth(), b.truth());
  EXPECT_GT(a.truth().distance, 50.0);  // it did drive
}

TEST(VehicleModel, ResetStartsOverExactlyLikeANewCar) {
  const VehicleParams p;
  const Pose2 start{-5.0, 10.0, -2.0};
  VehicleModel used(p);
  for (int i = 0; i < 1000; ++i) used.step(kDt, scripted(i));
  used.reset(start, 4.0, 100.0);

  const VehicleTruth& t = used.truth();
  EXPECT_EQ(t.t, 100.0);
  EXPECT_EQ(t.pose.x, start.x);
  EXPECT_EQ(t.pose.y, start.y);
  EXPECT_EQ(t.pose.yaw, start.yaw);
  EXPECT_EQ(t.vx, 4.0);
  EXPECT_EQ(t.vy, 0.0);
  EXPECT_EQ(t.yaw_rate, 0.0);
  EXPECT_EQ(t.steering, 0.0);
  EXPECT_EQ(t.distance, 0.0);
  EXPECT_EQ(t.roll, 0.0);
  EXPECT_EQ(t.pitch, 0.0);

  VehicleModel fresh(p);
  fresh.reset(start, 4.0, 100.0);
  for (int i = 0; i < 2000; ++i) {
    used.step(kDt, scripted(i));
    fresh.step(kDt, scripted(i));
  }
  expect_same(used.truth(), fresh.truth());
}

TEST(VehicleModel, SteeringFollowsDeadTimeThenRateLimit) {
  const VehicleParams p;  // dead time 0.05 s, 1.2 rad/s
  VehicleModel car(p);
  car.reset(Pose2{}, 5.0);
  const double request = 0.3;
  for (int i = 0; i < 100; ++i) {
    const double t_start = i * kDt;
    car.step(kDt, test::drive(5.0, request));
    const double end = (i + 1) * kDt;
    if (t_start < p.steer_dead_time - 1e-9) {
      EXPECT_EQ(car.truth().steering, 0.0) << "moved before the dead time, step " << i;
    } else {
      // Moving at the rate limit from the step the request came out of the dead time, until it arrives.
      const double expected = std::min(request, p.steer_max_rate * (end - p.steer_dead_time));
      EXPECT_NEAR(car.truth().steering, expected, 1e-9) << "step " << i;
    }
  }
  EXPECT_NEAR(car.truth().steering, request, 1e-12);
}

TEST(VehicleModel, SteeringRespectsAngleAndRateLimitsUnderAnyRequest) {
  const VehicleParams p;
  VehicleModel car(p);
  car.reset(Pose2{}, 8.0);
  double previous = 0.0, largest = 0.0;
  for (int i = 0; i < 2000; ++i) {
    // Bang-bang requests far outside the angle limit, switching faster than the actuator can follow.
    const double request = (i / 7) % 2 ? 2.0 : -2.0;
    car.step(kDt, test::drive(8.0, request));
    const double s = car.truth().steering;
    EXPECT_LE(std::abs(s - previous), p.steer_max_rate * kDt + 1e-12);
    EXPECT_LE(std::abs(s), p.steer_max_angle + 1e-12);
    largest = std::max(largest, std::abs(s));
    previous = s;
  }
  EXPECT_GT(largest, 0.03);  // it did move
  // Held long enough, the request is met at the angle limit.
  test::run_for(car, test::drive(3.0, 1.0), 2.0);
  EXPECT_NEAR(car.truth().steering, p.steer_max_angle, 1e-12);
}

TEST(VehicleModel, StandstillStaysAtRestInEveryMode) {
  const VehicleParams p;
  const Pose2 start{3.0, 4.0, 1.0};
  ActuatorCommand coast;
  coast.steering = 0.4;
  ActuatorCommand hold = test::drive(0.0, -0.4);
  ActuatorCommand brake;
  brake.max_brake = true;
  ActuatorCommand ebs = test::drive(5.0);
  ebs.ebs = true;
  for (const ActuatorCommand& cmd : {coast, hold, brake, ebs}) {
    VehicleModel car(p);
    car.reset(start);
    test::run_for(car, cmd, 10.0, [&](const VehicleTruth& t) {
      ASSERT_TRUE(all_finite(t));
      EXPECT_EQ(t.vx, 0.0);
      EXPECT_EQ(t.vy, 0.0);
      EXPECT_EQ(t.yaw_rate, 0.0);
      EXPECT_EQ(t.ax, 0.0);
      EXPECT_EQ(t.ay, 0.0);
      EXPECT_EQ(t.motor_torque, 0.0);
    });
    EXPECT_EQ(car.truth().pose.x, start.x);
    EXPECT_EQ(car.truth().pose.y, start.y);
    EXPECT_EQ(car.truth().pose.yaw, start.yaw);
    EXPECT_EQ(car.truth().distance, 0.0);
  }
}

TEST(VehicleModel, SpeedControllerTracksTheTargetThenStopsAndHolds) {
  const VehicleParams p;
  VehicleModel car(p);
  car.reset(Pose2{});
  test::run_for(car, test::drive(10.0), 10.0);
  EXPECT_NEAR(car.truth().vx, 10.0, 0.05);
  EXPECT_GT(car.truth().motor_torque, 0.0);
  EXPECT_EQ(car.truth().brake_force, 0.0);

  double stopped_at = -1;
  test::run_for(car, test::drive(0.0), 6.0, [&](const VehicleTruth& t) {
    if (stopped_at < 0 && t.vx == 0.0) stopped_at = t.t;
  });
  ASSERT_GT(stopped_at, 0.0) << "did not stop";
  // No faster than the tyres allow (10 m/s at μg takes 0.73 s), and a comfortable controlled stop.
  EXPECT_GT(stopped_at - 10.0, 10.0 / (p.mu * test::kG));
  EXPECT_LT(stopped_at - 10.0, 5.0);
  const Pose2 parked = car.truth().pose;
  test::run_for(car, test::drive(0.0), 5.0);
  EXPECT_EQ(car.truth().pose.x, parked.x);
  EXPECT_EQ(car.truth().pose.y, parked.y);
  EXPECT_GT(car.truth().brake_force, 0.0);  // held on the brakes
}

TEST(VehicleModel, DriveNeedsDriveEnabled) {
  const VehicleParams p;
  VehicleModel car(p);
  car.reset(Pose2{});
  ActuatorCommand cmd = test::drive(10.0);
  cmd.drive_enabled = false;
  test::run_for(car, cmd, 3.0);
  EXPECT_EQ(car.truth().vx, 0.0);
  EXPECT_EQ(car.truth().motor_torque, 0.0);
}

TEST(VehicleModel, LaunchWithSteeringThroughTheModelBlendIsSmooth) {
  // From standstill with full lock, slowly through the kinematic/dynamic blend to 6 m/s: the yaw rate changes
  // gradually and stays near the kinematic v·tan δ / L the whole way (no jumps, no NaN).
  const VehicleParams p;
  VehicleModel car(p);
  car.reset(Pose2{});
  ActuatorCommand cmd = test::drive(0.0, 0.35);
  double previous_r = 0;
  for (int i = 0; i < 2000; ++i) {
    cmd.target_speed = std::min(6.0, i * kDt * 1.0);  // 1 m/s² ramp
    car.step(kDt, cmd);
    const VehicleTruth& t = car.truth();
    ASSERT_TRUE(all_finite(t));
    EXPECT_LT(std::abs(t.yaw_rate - previous_r), 0.02) << "at " << t.vx << " m/s";
    if (t.t > 1.0) {
      const double kinematic = t.vx * std::tan(t.steering) / p.wheelbase;
      EXPECT_NEAR(t.yaw_rate, kinematic, 0.1 * kinematic) << "at " << t.vx << " m/s";
    }
    previous_r = t.yaw_rate;
  }
  EXPECT_NEAR(car.truth().vx, 6.0, 0.1);
}

TEST(VehicleModel, EmergencyBrakeInAFastCornerStopsWithinTheTyresLimits) {
  // EBS at the limit of grip in a corner: the car may spin (locked-up rear, no ABS against yaw), but the tyres
  // can never decelerate it harder than μ·(m g + downforce) plus drag, it comes to rest, and then stands still.
  const VehicleParams p;
  for (double v0 : {8.0, 15.0, 22.0}) {
    for (double steering : {0.05, 0.1, 0.2, 0.4}) {
      VehicleModel car(p);
      car.reset(Pose2{}, v0);
      ActuatorCommand cmd = test::drive(v0, steering);
      test::run_for(car, cmd, 5.0);
      const double t0 = car.truth().t, speed0 = car.truth().speed();
      cmd.ebs = true;
      auto grip_limit = [&](double v) {
        const double q = 0.5 * p.air_density * v * v;
        return (p.mu * (p.mass * test::kG + q * p.downforce_area) + q * p.drag_area) / p.mass +
               p.rolling_resistance * test::kG;
      };
      double stopped_at = -1;
      test::run_for(car, cmd, 6.0, [&](const VehicleTruth& t) {
        ASSERT_TRUE(all_finite(t));
        // 5 % for the lag of the load transfer and the blend of the two models.
        EXPECT_LT(std::hypot(t.ax, t.ay), 1.05 * grip_limit(t.speed())) << v0 << " m/s, δ " << steering;
        if (stopped_at < 0 && t.vx == 0 && t.vy == 0 && t.yaw_rate == 0) stopped_at = t.t;
      });
      ASSERT_GT(stopped_at, 0) << v0 << " m/s, δ " << steering << ": not at rest";
      EXPECT_GT(stopped_at - t0, speed0 / grip_limit(speed0)) << v0 << " m/s, δ " << steering;
      const Pose2 rest = car.truth().pose;
      test::run_for(car, cmd, 1.0);
      EXPECT_EQ(car.truth().pose.x, rest.x);
      EXPECT_EQ(car.truth().pose.yaw, rest.yaw);
    }
  }
}

TEST(VehicleModel, BodyAttitudeFromLoadTransfer) {
  const VehicleParams p;
  // Steady left turn: the body rolls to the right (roll +) by m·ay·h / k_roll.
  VehicleModel car(p);
  car.reset(Pose2{}, 12.0);
  test::run_for(car, test::drive(12.0, 0.08), 10.0);
  const VehicleTruth& t = car.truth();
  ASSERT_GT(t.ay, 3.0);
  EXPECT_NEAR(t.roll, p.mass * t.ay * p.cog_height / p.roll_stiffness, 1e-3 * std::abs(t.roll));
  EXPECT_GT(t.roll, 0.0);
  EXPECT_NEAR(t.pitch, 0.0, 1e-3);

  // Full braking: the nose dives (pitch +) by m·|ax|·h / k_pitch; about half a degree at μg.
  VehicleModel braking(p);
  braking.reset(Pose2{}, 15.0);
  ActuatorCommand stop;
  stop.max_brake = true;
  test::run_for(braking, stop, 0.5);
  const VehicleTruth& b = braking.truth();
  ASSERT_LT(b.ax, -p.mu * test::kG * 0.95);
  EXPECT_NEAR(b.pitch, -p.mass * b.ax * p.cog_height / p.pitch_stiffness, 0.02 * b.pitch);
  EXPECT_GT(b.pitch, deg2rad(0.4));
  EXPECT_LT(b.pitch, deg2rad(1.0));
  EXPECT_NEAR(b.brake_force, -b.ax * p.mass, 0.15 * b.brake_force);  // brakes give most of the deceleration
}

TEST(VehicleModel, WheelSpeedsFollowTheBodyMotion) {
  const VehicleParams p;
  VehicleModel car(p);
  car.reset(Pose2{}, 10.0);
  test::run_for(car, test::drive(10.0), 1.0);
  for (double w : car.truth().wheel_speeds) EXPECT_NEAR(w, car.truth().vx, 1e-9);

  test::run_for(car, test::drive(10.0, 0.1), 8.0);
  const VehicleTruth& t = car.truth();
  const auto& w = t.wheel_speeds;  // FL, FR, RL, RR
  // Rear wheels: forward speed ∓ yaw rate × half track; the outer (right) wheel of a left turn runs faster.
  EXPECT_NEAR(w[3] - w[2], t.yaw_rate * p.track_width, 1e-9);
  EXPECT_NEAR(0.5 * (w[2] + w[3]), t.vx, 1e-9);
  // Front wheels run on a larger radius than the rear ones, outer faster than inner.
  EXPECT_GT(w[1], w[0]);
  EXPECT_GT(w[0] + w[1], w[2] + w[3]);
}

TEST(VehicleModel, FootprintIsTheBodyOutlineAtThePose) {
  const VehicleParams p;  // body 2.9 × 1.4 m, 0.5 m behind the rear axle
  VehicleModel car(p);
  car.reset(Pose2{1.0, 2.0, std::numbers::pi / 2});  // facing +y: body x → map +y, body y → map −x
  const auto c = car.footprint();
  const double front = p.body_length - p.rear_overhang;
  const double half = p.body_width / 2;
  const Vec2 expected[4] = {{1.0 + half, 2.0 - p.rear_overhang},   // rear right
                            {1.0 + half, 2.0 + front},             // front right
                            {1.0 - half, 2.0 + front},             // front left
                            {1.0 - half, 2.0 - p.rear_overhang}};  // rear left
  for (int i = 0; i < 4; ++i) {
    EXPECT_NEAR(c[i].x(), expected[i].x(), 1e-12) << i;
    EXPECT_NEAR(c[i].y(), expected[i].y(), 1e-12) << i;
  }
}

TEST(VehicleModel, BadStepsAndCommandsAreRejectedWithoutHarm) {
  const VehicleParams p;
  VehicleModel car(p);
  car.reset(Pose2{}, 5.0);
  const VehicleTruth before = car.truth();
  for (double dt : {0.0, -0.01, std::nan(""), std::numeric_limits<double>::infinity(), 5.0})
    car.step(dt, test::drive(5.0));
  EXPECT_EQ(car.rejected_steps(), 5u);
  expect_same(car.truth(), before);

  ActuatorCommand nonsense = test::drive(std::nan(""), std::nan(""));
  test::run_for(car, nonsense, 2.0, [](const VehicleTruth& t) { ASSERT_TRUE(all_finite(t)); });
  // A NaN target is taken as "stop", a NaN steering request as "no change".
  EXPECT_LT(car.truth().vx, 5.0);
  EXPECT_EQ(car.truth().steering, 0.0);

  // A long step is split internally and gives the same motion as small steps.
  VehicleModel coarse(p), fine(p);
  coarse.reset(Pose2{}, 10.0);
  fine.reset(Pose2{}, 10.0);
  coarse.step(0.1, test::drive(10.0, 0.1));
  for (int i = 0; i < 20; ++i) fine.step(kDt, test::drive(10.0, 0.1));
  EXPECT_NEAR(coarse.truth().pose.x, fine.truth().pose.x, 1e-9);
  EXPECT_NEAR(coarse.truth().pose.y, fine.truth().pose.y, 1e-9);
}

TEST(VehicleParamsConfig, EveryFieldIsDeclaredWithUnitsAndTheDefaultsRoundTrip) {
  auto schema = std::make_shared<ConfigSchema>();
  vehicle_section().describe(*schema);
  EXPECT_EQ(schema->entries().size(), 35u);  // the car's own six (mass, wheelbase, body, lock) are car.*
  for (const auto& e : schema->entries()) {
    EXPECT_EQ(e.key.rfind("sim.vehicle.", 0), 0u) << e.key;
    EXPECT_FALSE(e.doc.empty()) << e.key;
    EXPECT_LT(e.min, e.max) << e.key;
  }
  EXPECT_EQ(schema->find("sim.vehicle.yaw_inertia")->unit, "kg·m²");

  Config cfg(schema);
  const VehicleParams d = vehicle_section().read(cfg);
  EXPECT_EQ(d.mass, VehicleParams{}.mass);
  EXPECT_EQ(d.mu, VehicleParams{}.mu);
  EXPECT_EQ(validate(d), "");

  cfg.set("sim.vehicle.mu", 0.9, "test");
  EXPECT_EQ(vehicle_section().read(cfg).mu, 0.9);
  EXPECT_THROW(cfg.set("sim.vehicle.mu", 7.0, "test"), ConfigError);
}

TEST(VehicleParamsConfig, InconsistentCarsAreRejectedByName) {
  VehicleParams p;
  p.cog_to_rear_axle = p.wheelbase + 0.1;
  EXPECT_NE(validate(p).find("cog_to_rear_axle"), std::string::npos);
  EXPECT_THROW(VehicleModel{p}, std::invalid_argument);

  VehicleParams q;
  q.kinematic_speed = 5.0;
  q.dynamic_speed = 4.0;
  EXPECT_NE(validate(q).find("kinematic_speed"), std::string::npos);

  VehicleParams r;
  r.mass = std::nan("");
  EXPECT_FALSE(validate(r).empty());
}

}  // namespace
}  // namespace fsd::sim
