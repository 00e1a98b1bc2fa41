#pragma once
// A headless `fsd run --sim` with a configuration of the test's, as a user runs it, and its scorecard: the pattern
// of the daemon's end-to-end source tests.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "tests/daemon/fsd_process.hpp"
#include "tests/scratch_dir.hpp"

namespace fsd::test {

// Runs `fsd run --sim --headless --until-finished --config <config> --report <scratch> <args>` (files named after
// `name`). Expects exit 0, or with `must_pass` false any judged run (never a refusal, exit 2). The report, or an
// empty value (a test failure) when none was written.
inline nlohmann::json sim_report(const std::string& name, const nlohmann::json& config, const std::string& args,
                                 bool must_pass = true, std::string* log_out = nullptr) {
  const std::string cfg = scratch_path(name + ".json"), report = scratch_path(name + "_report.json");
  std::ofstream(cfg) << config.dump();
  std::string log;
  const int rc =
      run_fsd("run --sim --headless --until-finished --config " + cfg + " --report " + report + " " + args, &log);
  if (must_pass)
    EXPECT_EQ(rc, 0) << log;
  else
    EXPECT_NE(rc, 2) << log;
  if (log_out) *log_out = log;
  std::ifstream f(report);
  if (!f) {
    ADD_FAILURE() << "no report: " << log;
    return {};
  }
  return nlohmann::json::parse(f);
}

}  // namespace fsd::test
