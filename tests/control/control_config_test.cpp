// The control configuration: every section declares its keys with defaults inside their bounds, and reading
// the defaults back gives the structs' own defaults; a file value overrides and is bounds-checked.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include <nlohmann/json.hpp>

#include "control/control_config.hpp"

namespace fsd {
namespace {

TEST(ControlConfig, DefaultsRoundTrip) {
  auto schema = std::make_shared<ConfigSchema>();
  describe_control(*schema);  // throws on a default outside its bounds or a duplicate key
  EXPECT_GT(schema->entries().size(), 80u);
  const Config cfg(schema);
  const AutopilotConfig c = read_control(cfg);
  const AutopilotConfig d;
  EXPECT_EQ(c.planner.walk.beam_width, d.planner.walk.beam_width);
  EXPECT_DOUBLE_EQ(c.planner.walk.w_length, d.planner.walk.w_length);
  EXPECT_DOUBLE_EQ(c.path.optimizer.w_curvature, d.path.optimizer.w_curvature);
  EXPECT_DOUBLE_EQ(c.guard.horizon, d.guard.horizon);
  EXPECT_EQ(c.follower.type, d.follower.type);
  EXPECT_DOUBLE_EQ(c.speed.mu, d.speed.mu);
  EXPECT_DOUBLE_EQ(c.supervisor.plan_timeout, d.supervisor.plan_timeout);
  EXPECT_DOUBLE_EQ(c.mission.acceleration_length, 75.0);
  EXPECT_DOUBLE_EQ(c.replan_period, d.replan_period);
  // Control's own keys and the car's description it reads (car.*).
  for (const auto& e : schema->entries())
    EXPECT_TRUE(e.key.rfind("control.", 0) == 0 || e.key.rfind("car.", 0) == 0) << e.key;
}

TEST(ControlConfig, OverridesAndBounds) {
  auto schema = std::make_shared<ConfigSchema>();
  describe_control(*schema);
  Config cfg(schema);
  cfg.merge(nlohmann::json::parse(R"({"control": {"follower": {"type": "stanley"}, "speed": {"v_max": 12.5}}})"),
            "test");
  const AutopilotConfig c = read_control(cfg);
  EXPECT_EQ(c.follower.type, "stanley");
  EXPECT_DOUBLE_EQ(c.speed.v_max, 12.5);
  EXPECT_THROW(cfg.set("control.speed.mu", 7.0, "test"), ConfigError);
  EXPECT_THROW(cfg.set("control.follower.type", "bang_bang", "test"), ConfigError);
  EXPECT_TRUE(schema->find("control.speed.v_max")->tunable);
  EXPECT_TRUE(schema->find("control.follower.pp_gain")->tunable);
}

TEST(ControlConfig, LapTwoHasItsOwnGainsAndFrictionShare) {
  auto schema = std::make_shared<ConfigSchema>();
  describe_control(*schema);
  Config cfg(schema);
  cfg.merge(
      nlohmann::json::parse(
          R"({"car": {"max_steer": 0.45}, "control": {"follower": {"lqr_r": 5}, "lap2": {"lqr_r": 0.7, "mu_margin": 0.9}}})"),
      "test");
  const AutopilotConfig c = read_control(cfg);
  EXPECT_DOUBLE_EQ(c.follower.lqr_r, 5.0);  // lap 1 keeps its own
  EXPECT_DOUBLE_EQ(c.lap2.mu_margin, 0.9);
  const FollowerConfig f2 = c.lap2.follower(c.follower);
  EXPECT_DOUBLE_EQ(f2.lqr_r, 0.7);
  EXPECT_DOUBLE_EQ(f2.max_steer, 0.45);  // the car's limits come from its description (car.*)
  EXPECT_THROW(cfg.set("control.lap2.mu_margin", 1.5, "test"), ConfigError);
}

// A live change through the section's member pointer gives what reading a configuration with that value gives,
// for every tunable key (each set to a value inside its bounds other than its default), copies included.
TEST(ControlConfig, LiveChangeEqualsReadingTheChangedConfiguration) {
  auto schema = std::make_shared<ConfigSchema>();
  describe_control(*schema);
  const Config defaults(schema);
  int tunables = 0;
  for (const auto& e : schema->entries()) {
    if (!e.tunable) continue;
    ++tunables;
    const double def = e.type == ValueType::Boolean ? (defaults.boolean(e.key) ? 1.0 : 0.0) : defaults.number(e.key);
    double v = e.type == ValueType::Boolean ? 1.0 - def : std::min(e.max, def + 1.0);
    if (v == def) v = std::max(e.min, def - 1.0);
    if (e.type == ValueType::Integer) v = std::round(v);
    Config changed = defaults;
    if (e.type == ValueType::Boolean)
      changed.set(e.key, v != 0.0, "test");
    else if (e.type == ValueType::Integer)
      changed.set(e.key, static_cast<long long>(v), "test");
    else
      changed.set(e.key, v, "test");
    AutopilotConfig live = read_control(defaults);
    ASSERT_TRUE(apply_control_param(live, e.key, v)) << e.key;
    ASSERT_NE(v, def) << e.key;
    EXPECT_EQ(control_param(live, e.key), v) << e.key;
    const AutopilotConfig read = read_control(changed);
    // Every number, integer and boolean key of the sections reads the same from both, the copies too.
    for (const auto& k : schema->entries()) {
      if (k.type == ValueType::String) continue;
      EXPECT_EQ(control_param(live, k.key), control_param(read, k.key)) << "after " << e.key << ": " << k.key;
    }
    // Lap 2's copy of the path settings and the guard's of the understeer follow a live change as a read does.
    EXPECT_EQ(live.trajectory.path.optimizer.clearance, read.trajectory.path.optimizer.clearance) << e.key;
    EXPECT_EQ(live.trajectory.path.accept_clearance, read.trajectory.path.accept_clearance) << e.key;
    EXPECT_EQ(live.trajectory.path.optimizer.w_centre, live.path.optimizer.w_centre) << e.key;
    EXPECT_EQ(live.guard.understeer, live.speed.understeer) << e.key;
  }
  EXPECT_GT(tunables, 20);
  AutopilotConfig c;
  EXPECT_FALSE(apply_control_param(c, "sim.vehicle.mass", 200.0));
  EXPECT_FALSE(apply_control_param(c, "control.no_such_key", 1.0));
}

}  // namespace
}  // namespace fsd
