#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "common/config.hpp"
#include "tests/scratch_dir.hpp"

namespace fsd {
namespace {

struct Sample {
  double speed = 5.0;
  int laps = 2;
  bool verbose = false;
  std::string mode = "fast";
};

ConfigSection<Sample> section() {
  return ConfigSection<Sample>("ctl")
      .number("speed", &Sample::speed, 0.0, 30.0, "m/s", "target speed", true)
      .integer("laps", &Sample::laps, 1, 10, "", "laps")
      .boolean("verbose", &Sample::verbose, "talk more")
      .string("mode", &Sample::mode, {"fast", "safe"}, "mode");
}

std::shared_ptr<const ConfigSchema> schema() {
  auto s = std::make_shared<ConfigSchema>();
  section().describe(*s);
  return s;
}

// The test's config file, named after the test.
std::filesystem::path config_file() {
  return test::scratch_path(std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + ".json");
}

std::string load_error(const std::string& text) {
  const auto path = config_file();
  std::ofstream(path) << text;
  try {
    Config::load(schema(), path);
  } catch (const ConfigError& e) {
    std::string msg = e.what();
    // Name the file as the test knows it.
    const auto p = msg.find(path.string());
    if (p != std::string::npos) msg.replace(p, path.string().size(), "FILE");
    return msg;
  }
  return "ok";
}

TEST(Config, DefaultsComeFromTheStruct) {
  const Config c(schema());
  const Sample s = section().read(c);
  EXPECT_EQ(s.speed, 5.0);
  EXPECT_EQ(s.laps, 2);
  EXPECT_FALSE(s.verbose);
  EXPECT_EQ(s.mode, "fast");
  EXPECT_EQ(c.as_json(), nlohmann::json::parse(R"({"ctl":{"speed":5.0,"laps":2,"verbose":false,"mode":"fast"}})"));
}

TEST(Config, FileOverridesOnlyItsKeys) {
  EXPECT_EQ(load_error(R"({"ctl": {"speed": 7.5}})"), "ok");
  const auto path = config_file();
  const Sample s = section().read(Config::load(schema(), path));
  EXPECT_EQ(s.speed, 7.5);
  EXPECT_EQ(s.laps, 2);
}

TEST(Config, RejectsEachKindOfBadInputNamingKeyAndFile) {
  EXPECT_EQ(load_error(R"({"ctl": {"sped": 7.5}})"), "FILE: unknown key 'ctl.sped'");
  EXPECT_EQ(load_error(R"({"control": {}})"), "FILE: unknown key 'control'");
  EXPECT_EQ(load_error(R"({"ctl": {"speed": "fast"}})"), "FILE: key 'ctl.speed': expected a number, got string");
  EXPECT_EQ(load_error(R"({"ctl": {"laps": 2.5}})"), "FILE: key 'ctl.laps': expected an integer, got 2.5");
  EXPECT_EQ(load_error(R"({"ctl": {"verbose": 1}})"), "FILE: key 'ctl.verbose': expected true or false, got number");
  EXPECT_EQ(load_error(R"({"ctl": {"speed": 31}})"), "FILE: key 'ctl.speed': value 31 out of range [0, 30] m/s");
  EXPECT_EQ(load_error(R"({"ctl": {"laps": 0}})"), "FILE: key 'ctl.laps': value 0 out of range [1, 10]");
  EXPECT_EQ(load_error(R"({"ctl": {"mode": "wild"}})"), "FILE: key 'ctl.mode': 'wild' is not one of: fast, safe");
  EXPECT_EQ(load_error(R"({"ctl": {"speed": {"x": 1}}})"), "FILE: key 'ctl.speed': expected a number, got object");
  EXPECT_EQ(load_error(R"([1, 2])"), "FILE: the configuration must be a JSON object");
  EXPECT_EQ(load_error(R"({"ctl": )").substr(0, 23), "FILE: not valid JSON: [");
  // A number beyond a double is nlohmann's out_of_range, not a parse_error (found by cone_model_fuzz).
  EXPECT_EQ(load_error(R"({"ctl": {"speed": 1e999}})").substr(0, 23), "FILE: not valid JSON: [");
  EXPECT_THROW(Config::load(schema(), "/nonexistent/fsd.json"), ConfigError);
}

TEST(Config, BadFileChangesNothing) {
  Config c(schema());
  EXPECT_THROW(c.merge(nlohmann::json::parse(R"({"ctl": {"speed": 9, "laps": 99}})"), "x"), ConfigError);
  EXPECT_EQ(c.number("ctl.speed"), 5.0);
}

TEST(Config, SchemaRejectsDuplicatesAndBadDefaults) {
  ConfigSchema s;
  section().describe(s);
  EXPECT_THROW(section().describe(s), std::logic_error);
  ConfigSchema s3;
  ConfigSection<Sample>("a").number("b", &Sample::speed, 0, 30, "", "").describe(s3);
  EXPECT_THROW(ConfigSection<Sample>("a.b").number("c", &Sample::speed, 0, 30, "", "").describe(s3), std::logic_error);
  ConfigSchema s2;
  EXPECT_THROW(ConfigSection<Sample>("x").number("speed", &Sample::speed, 10, 20, "", "").describe(s2),
               std::logic_error);
}

TEST(Config, MarkdownListsEveryKey) {
  const auto s = schema();
  const auto md = s->markdown();
  for (const auto& e : s->entries()) EXPECT_NE(md.find("`" + e.key + "`"), std::string::npos) << e.key;
}

}  // namespace
}  // namespace fsd
