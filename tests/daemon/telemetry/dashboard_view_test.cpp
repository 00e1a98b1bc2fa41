// The dashboard's view of the stack, shared by the car and the simulator: lap counts, running lap time and the
// driven lines, checked against hand-made control cycles.
#include <gtest/gtest.h>

#include "daemon/telemetry/dashboard_view.hpp"

namespace fsd {
namespace {

Autopilot idle_autopilot(Mission m) { return Autopilot(AutopilotConfig{}, m, ColourConvention{}); }

TEST(DashboardView, LapsTotalIsWhatTheMissionTimes) {
  const ControlOutput out;
  const auto skidpad = idle_autopilot(Mission::Skidpad);
  EXPECT_EQ(DashboardView(Mission::Skidpad, 2).snapshot(0, AsState::Off, out, skidpad, {}).as.laps_total, 4);
  const auto trackdrive = idle_autopilot(Mission::Trackdrive);
  EXPECT_EQ(DashboardView(Mission::Trackdrive, 10).snapshot(0, AsState::Off, out, trackdrive, {}).as.laps_total, 10);
  const auto accel = idle_autopilot(Mission::Acceleration);
  EXPECT_EQ(DashboardView(Mission::Acceleration, 10).snapshot(0, AsState::Off, out, accel, {}).as.laps_total, 1);
}

TEST(DashboardView, LapTimeRunsFromGoThenFromEachCrossing) {
  const auto ap = idle_autopilot(Mission::Trackdrive);
  DashboardView view(Mission::Trackdrive, 2);
  ControlOutput out;
  view.on_cycle(1.0, AsState::Ready, out, 0, Vec2(0, 0), 0);
  EXPECT_EQ(view.snapshot(2.0, AsState::Ready, out, ap, {}).as.lap_time, 0.0);  // not started before go
  view.on_cycle(5.0, AsState::Driving, out, 0, Vec2(0, 0), 1);
  EXPECT_DOUBLE_EQ(view.snapshot(7.5, AsState::Driving, out, ap, {}).as.lap_time, 2.5);
  out.lap = LapEvent{1, 40.0, 35.0};
  view.on_cycle(40.01, AsState::Driving, out, 1, Vec2(0, 0), 2);
  out.lap.reset();
  EXPECT_DOUBLE_EQ(view.snapshot(41.0, AsState::Driving, out, ap, {}).as.lap_time, 1.0);
}

TEST(DashboardView, LapIsTheOneBeingDrivenAndAfterTheFinishTheLastOne) {
  const auto ap = idle_autopilot(Mission::Trackdrive);
  DashboardView view(Mission::Trackdrive, 2);
  ControlOutput out;
  view.on_cycle(1.0, AsState::Driving, out, 0, Vec2(0, 0), 0);
  auto s = view.snapshot(2.0, AsState::Driving, out, ap, {});
  EXPECT_EQ(s.as.lap, 1);
  EXPECT_EQ(s.as.laps_completed, 0);
  out.lap = LapEvent{1, 30.0, 29.0};
  view.on_cycle(30.0, AsState::Driving, out, 1, Vec2(0, 0), 1);
  out.lap.reset();
  s = view.snapshot(31.0, AsState::Driving, out, ap, {});
  EXPECT_EQ(s.as.lap, 2);
  EXPECT_EQ(s.as.laps_completed, 1);
  EXPECT_DOUBLE_EQ(s.as.lap_time, 1.0);
  // The second crossing finishes the mission: lap 2/2 with its own time, not "lap 2/2 0:00.00".
  out.lap = LapEvent{2, 55.5, 25.5};
  out.finished = true;
  view.on_cycle(55.5, AsState::Driving, out, 2, Vec2(0, 0), 2);
  out.lap.reset();
  view.on_cycle(60.0, AsState::Finished, out, 2, Vec2(0, 0), 3);
  for (const double t : {56.0, 70.0}) {
    s = view.snapshot(t, AsState::Finished, out, ap, {});
    EXPECT_EQ(s.as.lap, 2);
    EXPECT_EQ(s.as.laps_completed, 2);
    EXPECT_DOUBLE_EQ(s.as.lap_time, 25.5);
    EXPECT_TRUE(s.as.finished);
  }
}

TEST(DashboardView, LapClockFreezesWhenTheCarStops) {
  const auto ap = idle_autopilot(Mission::Trackdrive);
  DashboardView view(Mission::Trackdrive, 2);
  const ControlOutput out;
  view.on_cycle(5.0, AsState::Driving, out, 0, Vec2(0, 0), 0);
  view.on_cycle(12.0, AsState::Driving, out, 0, Vec2(0, 0), 1);
  view.on_cycle(12.01, AsState::Emergency, out, 0, Vec2(0, 0), 2);
  for (const double t : {12.5, 20.0, 100.0}) {
    const auto s = view.snapshot(t, AsState::Emergency, out, ap, {});
    EXPECT_DOUBLE_EQ(s.as.lap_time, 7.01) << "at " << t;
    EXPECT_EQ(s.as.lap, 1);
  }
  view.on_cycle(101.0, AsState::Emergency, out, 0, Vec2(0, 0), 3);  // still stopped: still frozen
  EXPECT_DOUBLE_EQ(view.snapshot(102.0, AsState::Emergency, out, ap, {}).as.lap_time, 7.01);
}

TEST(DashboardView, TrailsSplitAtTheFirstLapAndStayBounded) {
  const auto ap = idle_autopilot(Mission::Trackdrive);
  DashboardView view(Mission::Trackdrive, 2);
  const ControlOutput out;
  // One point every 10 cycles while Driving: cycles 0..99 give 10 on lap 1.
  for (std::uint64_t c = 0; c < 100; ++c)
    view.on_cycle(0.01 * c, AsState::Driving, out, 0, Vec2(static_cast<double>(c), 0), c);
  view.on_cycle(1.0, AsState::Ready, out, 0, Vec2(1, 1), 100);      // not driving: nothing kept
  view.on_cycle(1.0, AsState::Driving, out, 0, std::nullopt, 110);  // no position yet: nothing kept
  auto s = view.snapshot(1.0, AsState::Driving, out, ap, {});
  ASSERT_EQ(s.paths->lap1_trajectory.size(), 10u);
  EXPECT_EQ(s.paths->lap1_trajectory[3], Vec2(30, 0));
  EXPECT_TRUE(s.paths->lap2_tracking.empty());
  for (std::uint64_t c = 0; c < 10 * (DashboardView::kMaxTrailPoints + 50); c += 10)
    view.on_cycle(2.0, AsState::Driving, out, 1, Vec2(0, 1), c);
  s = view.snapshot(3.0, AsState::Driving, out, ap, {});
  EXPECT_EQ(s.paths->lap1_trajectory.size(), 10u);
  EXPECT_EQ(s.paths->lap2_tracking.size(), DashboardView::kMaxTrailPoints);
}

TEST(DashboardView, ResAndEbsComeFromTheVcu) {
  const auto ap = idle_autopilot(Mission::Trackdrive);
  const DashboardView view(Mission::Trackdrive, 2);
  VcuStatus st;
  st.res_go = true;
  st.ebs_active = true;
  const auto s = view.snapshot(0, AsState::Driving, ControlOutput{}, ap, st);
  EXPECT_TRUE(s.as.res_go);
  EXPECT_TRUE(s.as.ebs_active);
  EXPECT_FALSE(s.as.res_emergency);
  EXPECT_EQ(s.as.as_state, AsState::Driving);
}

// The true path (sim runs): the truth's positions while Driving, 0.1 m apart at least; the same pointer while it
// did not grow, so the channel sends nothing new.
TEST(DashboardView, TheTruePathFollowsTheTruthWhileDriving) {
  const auto ap = idle_autopilot(Mission::Trackdrive);
  DashboardView view(Mission::Trackdrive, 2);
  const ControlOutput out;
  const auto snap = [&](AsState as, double x) {
    TelemetrySnapshot s = view.snapshot(0, as, out, ap, {});
    s.truth = web::TruthState{};
    s.truth->pose = {x, 1.0, 0.0};
    view.add_truth_path(s);
    return s.truth_path;
  };
  EXPECT_EQ(snap(AsState::Ready, 0.0), nullptr);  // standing before go: nothing
  EXPECT_EQ(snap(AsState::Driving, 0.0), nullptr);  // one point is no path
  const auto two = snap(AsState::Driving, 0.5);
  ASSERT_NE(two, nullptr);
  EXPECT_EQ(*two, (std::vector<Vec2>{{0.0, 1.0}, {0.5, 1.0}}));
  EXPECT_EQ(snap(AsState::Driving, 0.55), two);  // 5 cm on: not a new point, not a new message
  const auto three = snap(AsState::Driving, 0.7);
  ASSERT_NE(three, two);
  EXPECT_EQ(three->back(), Vec2(0.7, 1.0));
  EXPECT_EQ(snap(AsState::Emergency, 5.0), three);  // stopped driving: the path stays as it was
  TelemetrySnapshot no_truth = view.snapshot(0, AsState::Driving, out, ap, {});
  view.add_truth_path(no_truth);  // the car: no truth, no path
  EXPECT_EQ(no_truth.truth_path, nullptr);
}

}  // namespace
}  // namespace fsd
