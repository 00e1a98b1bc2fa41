#pragma once
// `fsd run --sim --headless --until-finished` on a shared track with a config of the test's, and the scorecard it
// wrote (docs/scorecard.md), for the daemon's end-to-end tests. The run's output goes into the failure message.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "tests/daemon/fsd_process.hpp"
#include "tests/scratch_dir.hpp"

namespace fsd::test {

// `name` names the scratch files; `track` is a file of ../shared/tracks without ".csv". With `must_pass` the run
// must exit 0 (verdict pass); else only not be refused (exit 2). An empty object when no report was written.
inline nlohmann::json sim_report(const std::string& name, const nlohmann::json& config, const std::string& track,
                                 int laps, bool must_pass = true, std::string* log_out = nullptr) {
  const std::string cfg = scratch_path(name + ".json"), report = scratch_path(name + "_report.json");
  std::ofstream(cfg) << config.dump();
  std::string log;
  const int rc = run_fsd("run --sim --headless --until-finished --laps " + std::to_string(laps) +
                             " --track ../shared/tracks/" + track + ".csv --config " + cfg + " --report " + report,
                         &log);
  if (must_pass)
    EXPECT_EQ(rc, 0) << log;
  else
    EXPECT_NE(rc, 2) << log;  // a run, judged or not; never refused
  if (log_out) *log_out = log;
  std::ifstream f(report);
  if (!f) {
    ADD_FAILURE() << "no report: " << log;
    return nlohmann::json::object();
  }
  return nlohmann::json::parse(f);
}

}  // namespace fsd::test
