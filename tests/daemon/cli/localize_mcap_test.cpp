// `fsd localize --mcap FILE`: the fusion filter on a recording's NMEA and VCU frames, scored against the ground
// truth the same recording holds (the virtual car's true state, /raw/truth_state).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>
#include <string>

#include "common/mcap/byte_io.hpp"
#include "daemon/feeders/truth_frames.hpp"
#include "daemon/recording/recording_reader.hpp"
#include "tests/daemon/fsd_process.hpp"
#include "tests/scratch_dir.hpp"
#include "tests/truth_sources.hpp"

namespace fsd {
namespace {

TEST(LocalizeMcap, TheFusedTrajectoryOfARecordingFollowsItsTruth) {
  const auto cfg = test::scratch_path("loc_mcap_cfg.json");
  std::ofstream(cfg) << test::truth_sources();
  const auto rec = test::scratch_path("loc_mcap.mcap");
  std::string out;
  ASSERT_EQ(test::run_fsd("run --sim --headless --until-finished --mission acceleration --track "
                          "../shared/tracks/epfl_acceleration.csv --config " +
                              cfg + " --record " + rec,
                          &out),
            0)
      << out;
  const auto traj = test::scratch_path("loc_mcap.csv");
  ASSERT_EQ(test::run_fsd("localize --mcap " + rec + " --filter ekf --out " + traj, &out), 0) << out;

  // The truth, by receive time (one state per cycle).
  std::map<long long, Pose2> truth;
  {
    mcap::MappedFile mapped(rec);
    RecordingReader reader(mapped.bytes());
    while (const auto e = reader.next())
      if (e->kind == RecordingEvent::Kind::Frame && e->channel == RawChannel::TruthState)
        if (const auto s = decode_truth_state(e->bytes)) truth[std::llround(e->t * 1000)] = s->state.pose;
  }
  ASSERT_GT(truth.size(), 500u);
  std::ifstream f(traj);
  std::string line;
  std::getline(f, line);
  EXPECT_EQ(line, "t_unix_s,east_m,north_m,yaw_rad");
  double sum2 = 0, worst = 0, travelled_to = 0;
  int n = 0;
  while (std::getline(f, line)) {
    double t, x, y, yaw;
    char c;
    std::istringstream row(line);
    ASSERT_TRUE(row >> t >> c >> x >> c >> y >> c >> yaw) << line;
    // The truth at t, between the two cycles around it (10 ms apart: up to 0.2 m at speed).
    const auto hi = truth.lower_bound(static_cast<long long>(std::ceil(t * 1000)));
    if (hi == truth.end() || hi == truth.begin()) continue;
    const auto lo = std::prev(hi);
    const double w = (t * 1000 - static_cast<double>(lo->first)) / static_cast<double>(hi->first - lo->first);
    if (w < 0 || w > 1) continue;
    const double tx = lo->second.x + w * (hi->second.x - lo->second.x);
    const double ty = lo->second.y + w * (hi->second.y - lo->second.y);
    const auto it = hi;
    const double e = std::hypot(x - tx, y - ty);
    sum2 += e * e;
    worst = std::max(worst, e);
    travelled_to = std::max(travelled_to,
                            std::hypot(it->second.x - truth.begin()->second.x, it->second.y - truth.begin()->second.y));
    ++n;
  }
  ASSERT_GT(n, 500);
  EXPECT_GT(travelled_to, 75.0);  // the whole acceleration lane
  EXPECT_LT(std::sqrt(sum2 / n), 0.10);
  EXPECT_LT(worst, 0.30);
}

TEST(LocalizeMcap, WhatDoesNotApplyAndWhatIsNoRecordingExitTwo) {
  std::string out;
  const auto not_mcap = test::scratch_path("not_a_recording.mcap");
  std::ofstream(not_mcap) << "hello";
  EXPECT_EQ(test::run_fsd("localize --mcap " + not_mcap + " --out " + test::scratch_path("x.csv"), &out), 2) << out;
  EXPECT_NE(out.find("not_a_recording.mcap"), std::string::npos) << out;
  EXPECT_EQ(test::run_fsd("localize --mcap " + not_mcap + " --imu ../shared/data/amz_2017/imu.csv --out " +
                              test::scratch_path("x.csv"),
                          &out),
            2)
      << out;
  EXPECT_NE(out.find("--mcap takes the sensors"), std::string::npos) << out;
  EXPECT_EQ(test::run_fsd("localize --out " + test::scratch_path("x.csv"), &out), 2) << out;
  EXPECT_NE(out.find("--imu and --speed are required"), std::string::npos) << out;
}

}  // namespace
}  // namespace fsd
