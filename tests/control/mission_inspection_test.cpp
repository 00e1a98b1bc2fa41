// InspectionMission alone: a sine sweep of the steering, wheels turning slowly, for inspection_duration; no path,
// no cones, no planner.
#include <gtest/gtest.h>

#include <cmath>

#include "control/missions/mission_inspection.hpp"
#include "tests/control/mission_world.hpp"

namespace fsd {
namespace {

TEST(InspectionMission, SweepsTheSteeringThenFinishes) {
  AutopilotConfig config;  // 25 s, 4 s a sweep, 0.8 of the lock, 1 m/s
  InspectionMission run(config);
  EXPECT_FALSE(run.uses_planner());
  EXPECT_FALSE(run.needs_perception());
  test::MissionWorld world;
  world.move(0.0, {0.0, 0.0}, 0, 0);
  ControlCommand cmd;
  cmd.steering = 0.3;
  cmd.target_speed = 5.0;
  run.limit(world.input(5.0), cmd);  // before the start: wheel straight, wheels turning
  EXPECT_EQ(cmd.steering, 0.0);
  EXPECT_EQ(cmd.target_speed, 1.0);

  run.start(world.input(10.0));
  const MissionPath p = run.update_path(world.input(10.0));
  EXPECT_EQ(p.path, nullptr);
  EXPECT_FALSE(p.fixed);
  const double lock = 0.8 * config.follower.max_steer;
  for (const auto& [t, steering] : {std::pair{11.0, lock}, std::pair{12.0, 0.0}, std::pair{13.0, -lock},
                                    std::pair{14.0, 0.0}, std::pair{34.0, 0.0}}) {
    cmd = {};
    run.limit(world.input(t), cmd);
    EXPECT_NEAR(cmd.steering, steering, 1e-9) << t;
    EXPECT_EQ(cmd.target_speed, 1.0) << t;
  }
  EXPECT_TRUE(run.progress(world.input(34.9), nullptr).laps.empty());
  EXPECT_FALSE(run.finished());
  EXPECT_TRUE(run.progress(world.input(35.0), nullptr).laps.empty());  // no lap: a run of its own kind
  EXPECT_TRUE(run.finished());
  cmd = {};
  run.limit(world.input(35.5), cmd);
  EXPECT_EQ(cmd.target_speed, 0.0);
}

TEST(NoMission, HoldsTheCar) {
  NoMission run(AutopilotConfig{});
  test::MissionWorld world;
  world.move(0.0, {0.0, 0.0}, 0, 0);
  run.start(world.input(0.0));
  EXPECT_EQ(run.update_path(world.input(1.0)).path, nullptr);
  EXPECT_TRUE(run.progress(world.input(100.0), nullptr).laps.empty());
  EXPECT_FALSE(run.finished());
}

}  // namespace
}  // namespace fsd
