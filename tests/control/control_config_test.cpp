// The control configuration: every section declares its keys with defaults inside their bounds, and reading
// the defaults back gives the structs' own defaults; a file value overrides and is bounds-checked.
#include <gtest/gtest.h>

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
  EXPECT_EQ(c.planner.beam_width, d.planner.beam_width);
  EXPECT_DOUBLE_EQ(c.planner.w_length, d.planner.w_length);
  EXPECT_EQ(c.follower.type, d.follower.type);
  EXPECT_DOUBLE_EQ(c.speed.mu, d.speed.mu);
  EXPECT_DOUBLE_EQ(c.supervisor.plan_timeout, d.supervisor.plan_timeout);
  EXPECT_DOUBLE_EQ(c.mission.acceleration_length, 75.0);
  EXPECT_DOUBLE_EQ(c.replan_period, d.replan_period);
  for (const auto& e : schema->entries()) EXPECT_EQ(e.key.rfind("control", 0), 0u) << e.key;
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
  cfg.merge(nlohmann::json::parse(
                R"({"control": {"follower": {"lqr_r": 5, "max_steer": 0.45}, "lap2": {"lqr_r": 0.7, "mu_margin": 0.9}}})"),
            "test");
  const AutopilotConfig c = read_control(cfg);
  EXPECT_DOUBLE_EQ(c.follower.lqr_r, 5.0);  // lap 1 keeps its own
  EXPECT_DOUBLE_EQ(c.lap2.mu_margin, 0.9);
  const FollowerConfig f2 = c.lap2.follower(c.follower);
  EXPECT_DOUBLE_EQ(f2.lqr_r, 0.7);
  EXPECT_DOUBLE_EQ(f2.max_steer, 0.45);  // the car's limits come from control.follower
  EXPECT_THROW(cfg.set("control.lap2.mu_margin", 1.5, "test"), ConfigError);
}

}  // namespace
}  // namespace fsd
