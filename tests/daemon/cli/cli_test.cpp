// The fsd command line as a user runs it: the real binary, its output and exit status.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "daemon/stack/settings.hpp"
#include "tests/daemon/fsd_process.hpp"
#include "tests/scratch_dir.hpp"
#include "tests/truth_sources.hpp"

namespace fsd {
namespace {

struct Result {
  int status;
  std::string out;
};

Result run(const std::string& args) {
  Result r;
  r.status = test::run_fsd(args, &r.out);
  return r;
}

TEST(Cli, HelpAndVersion) {
  const auto help = run("--help");
  EXPECT_EQ(help.status, 0);
  EXPECT_NE(help.out.find("version"), std::string::npos);
  const auto v = run("version");
  EXPECT_EQ(v.status, 0);
  EXPECT_EQ(v.out, std::string("fsd ") + FSD_VERSION + "\n");
}

TEST(Cli, BadUsageExitsTwo) {
  EXPECT_EQ(run("").status, 2);
  const auto unknown = run("no-such-command");
  EXPECT_EQ(unknown.status, 2);
  EXPECT_NE(unknown.out.find("unknown subcommand 'no-such-command'"), std::string::npos) << unknown.out;
  EXPECT_EQ(run("version --bogus").status, 2);
}

TEST(Cli, CommittedDefaultConfigEqualsTheSchemaDefaults) {
  std::ifstream f("deploy/config/default.json");
  ASSERT_TRUE(f) << "deploy/config/default.json missing";
  const auto file = nlohmann::json::parse(f);
  EXPECT_EQ(file, config_schema()->defaults()) << "regenerate with: fsd config defaults > deploy/config/default.json";
  EXPECT_EQ(run("config check deploy/config/default.json").status, 0);
}

TEST(Cli, ConfigurationDocsListEveryKey) {
  std::ifstream f("docs/configuration.md");
  ASSERT_TRUE(f);
  const std::string doc((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  EXPECT_NE(doc.find(config_schema()->markdown()), std::string::npos) << "regenerate the table with: fsd config doc";
}

TEST(Cli, ConfigCheckNamesTheBadKey) {
  const std::string path = test::scratch_path("bad_config.json");
  std::ofstream(path) << R"({"run": {"laps": 0}})";
  const auto r = run("config check " + path);
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.out.find("key 'run.laps': value 0 out of range [1, 100]"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find(path), std::string::npos);
}

TEST(Cli, ConfigCheckListsEveryError) {
  const std::string path = test::scratch_path("bad_config_many.json");
  std::ofstream(path) << R"({"run": {"laps": 0, "mission": "drag_race", "bogus": 1}, "nope": {"x": 1}})";
  const auto r = run("config check " + path);
  EXPECT_EQ(r.status, 2);
  for (const char* why :
       {"key 'run.laps': value 0 out of range", "key 'run.mission'", "unknown key 'run.bogus'", "unknown key 'nope'"})
    EXPECT_NE(r.out.find(why), std::string::npos) << why << " in\n" << r.out;
}

// A desk run's dashboard stays on the machine; a configuration file that sets web.bind is obeyed.
TEST(Cli, TheVirtualCarsDashboardBindsTheLoopbackUnlessConfigured) {
  const std::string quick = test::scratch_path("bind_quick.json");
  std::ofstream(quick) << test::truth_sources({{"run", {{"max_sim_time", 1}}}});
  const auto local = run("run --sim --port 0 --config " + quick);
  EXPECT_NE(local.out.find("dashboard on http://127.0.0.1:"), std::string::npos) << local.out;
  const std::string open = test::scratch_path("bind_open.json");
  std::ofstream(open) << test::truth_sources({{"run", {{"max_sim_time", 1}}}, {"web", {{"bind", "0.0.0.0"}}}});
  const auto all = run("run --sim --port 0 --config " + open);
  EXPECT_NE(all.out.find("dashboard on http://0.0.0.0:"), std::string::npos) << all.out;
}

}  // namespace
}  // namespace fsd
