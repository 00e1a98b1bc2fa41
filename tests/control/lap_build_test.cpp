// Lap 2's path built away from the control step (Autopilot::set_lap_builder), in closed loop on the tests'
// bicycle car: while the build is out, lap 1's planning drives on; the lap is taken when it arrives, also when it
// arrives after the line; a real worker thread gives the same two clean laps. And re-tuning during lap 2 keeps
// the lap's own speed profile.
#include <gtest/gtest.h>

#include <chrono>
#include <deque>
#include <future>
#include <memory>
#include <optional>
#include <utility>

#include "tests/control/mission_harness.hpp"

namespace fsd {
namespace {

const auto bicycle_config = test::bicycle_autopilot_config;

// A lap builder that holds each job until the test releases it `delay` control cycles later.
struct DeferredBuilder final : LapBuildService {
  int delay = 0;
  struct Job {
    int due;
    LapBuildJob job;
  };
  std::deque<Job> jobs;
  std::optional<TrajectoryResult> done;
  int cycle = 0, requests = 0;
  std::vector<double> requested_at, delivered_at;

  bool submit(LapBuildJob job) override {
    ++requests;
    jobs.push_back({cycle + delay, std::move(job)});
    return true;
  }
  std::optional<TrajectoryResult> poll() override { return std::exchange(done, std::nullopt); }
  // After each control cycle.
  void tick(double t) {
    ++cycle;
    while (!jobs.empty() && jobs.front().due <= cycle) {
      done = jobs.front().job();
      jobs.pop_front();
      delivered_at.push_back(t);
    }
  }
};

// A real worker thread per job, as the daemon runs it.
struct ThreadBuilder final : LapBuildService {
  int requests = 0;
  std::future<TrajectoryResult> pending;
  bool submit(LapBuildJob job) override {
    ++requests;
    pending = std::async(std::launch::async, std::move(job));
    return true;
  }
  std::optional<TrajectoryResult> poll() override {
    if (!pending.valid() || pending.wait_for(std::chrono::seconds(0)) != std::future_status::ready) return std::nullopt;
    return pending.get();
  }
};

struct Outcome {
  std::vector<std::pair<double, PathSource>> sources;
  std::vector<double> lap_lines;
};

void expect_two_clean_laps(const test::MissionHarness& h) {
  ASSERT_EQ(h.laps().size(), 2u);
  EXPECT_EQ(h.as_state(), AsState::Finished);
  EXPECT_EQ(h.cones_hit(), 0);
  EXPECT_LT(h.laps()[1].time_s, 0.8 * h.laps()[0].time_s);
  const auto [rms2, max2] = h.lap_cte(2);
  EXPECT_LT(rms2, 0.15);
  EXPECT_LT(max2, 0.5);
}

TEST(LapBuild, WhileTheBuildIsOutLapOnePlanningDrivesThenTheLapIsTaken) {
  const Track track = test::shared_track("epfl_track_1");
  DeferredBuilder b;
  b.delay = 5;  // 0.1 s at the harness's 50 Hz
  Outcome o;
  test::HarnessOptions options;
  options.observe = [&](double t, const ControlOutput& out, const test::BicycleSim&) {
    o.sources.emplace_back(t, out.source);
    if (out.lap_line) o.lap_lines.push_back(t);
    if (b.jobs.size() == 1 && b.jobs.front().due == b.cycle + b.delay) b.requested_at.push_back(t);
    b.tick(t);
  };
  test::MissionHarness h(track, Mission::Trackdrive, bicycle_config(), options);
  h.autopilot().set_lap_builder(&b);
  h.run();
  expect_two_clean_laps(h);
  // One build, before the line (the early build), taken the cycle after it was delivered, 5 cycles on.
  ASSERT_EQ(b.requests, 1);
  ASSERT_EQ(b.requested_at.size(), 1u);
  ASSERT_EQ(o.lap_lines.size(), 1u);
  EXPECT_NEAR(o.lap_lines[0] - b.requested_at[0], 5 * 0.02, 1e-6);  // taken at the step after the 5th
  EXPECT_LT(o.lap_lines[0], h.laps()[0].t);
  // Until then the car drove on the real-time plan, from the next cycle on the recorded lap.
  for (const auto& [t, source] : o.sources) {
    if (t <= o.lap_lines[0] && t > 6.0) {
      EXPECT_EQ(source, PathSource::Planner) << t;
    } else if (t > o.lap_lines[0] && t < h.laps()[1].t) {
      EXPECT_EQ(source, PathSource::Recorded) << t;
    }
  }
}

TEST(LapBuild, AnEarlyBuildStillOutAtTheLineIsTakenAfterIt) {
  // 4 s: the early build starts 25 m before the line at lap 1's ≤ 8 m/s, so it is still out at the crossing.
  const Track track = test::shared_track("epfl_track_1");
  DeferredBuilder b;
  b.delay = 200;
  std::vector<double> lap_lines;
  test::HarnessOptions options;
  options.observe = [&](double t, const ControlOutput& out, const test::BicycleSim&) {
    if (out.lap_line) lap_lines.push_back(t);
    b.tick(t);
  };
  test::MissionHarness h(track, Mission::Trackdrive, bicycle_config(), options);
  h.autopilot().set_lap_builder(&b);
  h.run();
  // The crossing did not start a second build; the first was taken after the line, and lap 2 ran on it.
  EXPECT_EQ(b.requests, 1);
  ASSERT_EQ(lap_lines.size(), 1u);
  ASSERT_GE(h.laps().size(), 1u);
  EXPECT_GT(lap_lines[0], h.laps()[0].t);
  expect_two_clean_laps(h);
  EXPECT_TRUE(h.autopilot().faults().empty());
}

TEST(LapBuild, OnAWorkerThreadTheTwoLapsAreTheSame) {
  const Track track = test::shared_track("epfl_track_1");
  ThreadBuilder builder;
  test::MissionHarness h(track, Mission::Trackdrive, bicycle_config());
  h.autopilot().set_lap_builder(&builder);
  h.run();
  EXPECT_EQ(builder.requests, 1);
  expect_two_clean_laps(h);
  EXPECT_NE(h.autopilot().recorded_path(), nullptr);
}

TEST(LapBuild, RetuningDuringLapTwoKeepsTheLapsOwnSpeeds) {
  // epfl_autoX_Vaudoise_Sponso's lap path has hairpins at the steering's reach, slowed by the steering's limit,
  // and runs at control.lap2.mu_margin of μ. A live parameter change re-profiles the lap with the new limits: with
  // the same values, the same speeds (it used to take the known-straight share of μ).
  const Track track = test::shared_track("epfl_autoX_Vaudoise_Sponso");
  const AutopilotConfig config = bicycle_config();
  std::vector<double> before, after;
  bool retuned = false;
  test::MissionHarness* harness = nullptr;
  test::HarnessOptions options;
  options.observe = [&](double, const ControlOutput& out, const test::BicycleSim&) {
    const Path* lap = harness->autopilot().recorded_path();
    if (retuned || !lap || out.source != PathSource::Recorded) return;
    for (const auto& q : lap->points) before.push_back(q.v);
    harness->autopilot().set_config(config);
    for (const auto& q : harness->autopilot().recorded_path()->points) after.push_back(q.v);
    retuned = true;
  };
  test::MissionHarness h(track, Mission::Trackdrive, config, options);
  harness = &h;
  h.run();
  ASSERT_TRUE(retuned);
  ASSERT_EQ(before.size(), after.size());
  double v_min = 1e9;
  for (std::size_t i = 0; i < before.size(); ++i) {
    EXPECT_NEAR(after[i], before[i], 1e-9) << i;
    v_min = std::min(v_min, after[i]);
  }
  // The hairpins are there: taken at their friction limit √(0.97 · μ g / κ), κ near the lock's 0.36 (this bicycle does
  // not understeer, so its steering does not slow it further).
  EXPECT_LT(v_min, 6.0);
}

}  // namespace
}  // namespace fsd
