#include <gtest/gtest.h>

#include "tests/web/test_client.hpp"
#include "web/params_json.hpp"

namespace fsd::web {
namespace {

using nlohmann::json;

TEST(ParamsJson, TypedValuesFollowTheSchema) {
  Config cfg(test::test_schema());
  ParamRegistry reg(cfg);
  const auto all = parameters_json(reg, {});
  ASSERT_EQ(all.size(), 3u);
  std::vector<std::string> unknown;
  const auto some = parameters_json(reg, {"control.use_gnss", "x.y"}, &unknown);
  ASSERT_EQ(some.size(), 1u);
  EXPECT_EQ(some[0], (json{{"name", "control.use_gnss"}, {"value", true}}));
  EXPECT_EQ(unknown, std::vector<std::string>{"x.y"});
}

TEST(ParamsJson, ConversionChecksTypeAndBounds) {
  Config cfg(test::test_schema());
  ParamRegistry reg(cfg);
  std::map<std::string, const ConfigEntry*> e;
  for (const auto& i : reg.list()) e[i.entry->key] = i.entry;
  std::string err;
  EXPECT_EQ(parameter_from_json(*e["control.lookahead_points"], json(12.0), err), 12.0);  // whole float64 ok
  EXPECT_FALSE(parameter_from_json(*e["control.lookahead_points"], json(12.5), err));
  EXPECT_FALSE(parameter_from_json(*e["control.lookahead_points"], json(51), err));
  EXPECT_NE(err.find("out of range"), std::string::npos);
  EXPECT_EQ(parameter_from_json(*e["control.use_gnss"], json(false), err), 0.0);
  EXPECT_FALSE(parameter_from_json(*e["control.use_gnss"], json("yes"), err));
  EXPECT_FALSE(parameter_from_json(*e["control.target_speed"], json(), err));
  EXPECT_NE(err.find("cannot be unset"), std::string::npos);
  EXPECT_FALSE(parameter_from_json(*e["control.target_speed"], json(-0.1), err));
}

TEST(ParamsJson, ApplyIsAllOrNothing) {
  Config cfg(test::test_schema());
  ParamRegistry reg(cfg);
  auto r = apply_parameters(reg, {{"control.target_speed", 3.0}, {"nope", 1}}, "t");
  EXPECT_FALSE(r.ok);
  EXPECT_DOUBLE_EQ(*reg.get("control.target_speed"), 5.0);
  r = apply_parameters(reg, {{"control.target_speed", 3.0}, {"control.lookahead_points", 4}}, "t");
  EXPECT_TRUE(r.ok);
  EXPECT_EQ(r.applied, (std::vector<std::string>{"control.target_speed", "control.lookahead_points"}));
  EXPECT_DOUBLE_EQ(*reg.get("control.lookahead_points"), 4.0);
}

}  // namespace
}  // namespace fsd::web
