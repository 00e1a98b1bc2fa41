// The AS supervisor: motion only in Driving, Ready asked only when healthy at standstill, watchdogs on each
// stream and on the planner, controlled stop then Emergency, Finished only at standstill after the finish,
// and the fault log (once per onset, with time, source, what and action).
#include <gtest/gtest.h>

#include "control/supervisor/as_supervisor.hpp"

namespace fsd {
namespace {

VcuStatus vcu(Stamp t, AsState s) {
  VcuStatus v;
  v.stamp = t;
  v.as_state = s;
  v.mission = Mission::Trackdrive;
  return v;
}

void feed_all(AsSupervisor& sup, Stamp t, AsState s) {
  sup.on_vcu(vcu(t, s));
  sup.heartbeat(InputStream::Pose, t);
  sup.heartbeat(InputStream::Lidar, t);
  sup.on_plan(t, true);
}

TEST(AsSupervisor, NoMotionOutsideDriving) {
  for (const AsState s : {AsState::Off, AsState::Ready, AsState::Emergency, AsState::Finished}) {
    AsSupervisor sup;
    sup.set_mission(Mission::Trackdrive);
    for (double t = 0; t < 2; t += 0.1) {
      feed_all(sup, t, s);
      const auto d = sup.evaluate(t, 0.0, false);
      EXPECT_FALSE(d.may_move) << to_string(s);
      EXPECT_EQ(d.speed_cap, 0.0);
    }
  }
}

TEST(AsSupervisor, AsksForReadyOnlyWhenHealthyAndStanding) {
  AsSupervisor sup;
  sup.set_mission(Mission::Trackdrive);
  feed_all(sup, 0.0, AsState::Off);
  EXPECT_EQ(sup.evaluate(0.0, 0.0, false).request, AsRequest::None);  // not yet standing for 0.5 s
  feed_all(sup, 1.0, AsState::Off);
  EXPECT_EQ(sup.evaluate(1.0, 0.0, false).request, AsRequest::Ready);
  // No LiDAR for a while: not healthy.
  sup.on_vcu(vcu(2.0, AsState::Off));
  sup.heartbeat(InputStream::Pose, 2.0);
  EXPECT_EQ(sup.evaluate(2.0, 0.0, false).request, AsRequest::None);
  // Rolling: no Ready.
  feed_all(sup, 3.0, AsState::Off);
  EXPECT_EQ(sup.evaluate(3.0, 1.0, false).request, AsRequest::None);
  // No mission: no Ready.
  AsSupervisor none;
  feed_all(none, 0, AsState::Off);
  feed_all(none, 1, AsState::Off);
  EXPECT_EQ(none.evaluate(1.0, 0.0, false).request, AsRequest::None);
}

TEST(AsSupervisor, StalePoseStopsThenAsksForEmergencyAtStandstill) {
  AsSupervisor sup;
  sup.set_mission(Mission::Trackdrive);
  double t = 0;
  for (; t < 1.0; t += 0.01) {
    feed_all(sup, t, AsState::Driving);
    EXPECT_TRUE(sup.evaluate(t, 5.0, false).may_move);
  }
  // The pose stops arriving; everything else keeps coming.
  const double last_pose = t - 0.01;
  Supervision d;
  for (; t < 1.5; t += 0.01) {
    sup.on_vcu(vcu(t, AsState::Driving));
    sup.heartbeat(InputStream::Lidar, t);
    sup.on_plan(t, true);
    d = sup.evaluate(t, 5.0, false);
    if (t - last_pose <= 0.2 - 1e-9) {
      EXPECT_TRUE(d.may_move) << t;
    }
  }
  EXPECT_FALSE(d.may_move);
  EXPECT_TRUE(d.controlled_stop);
  EXPECT_EQ(d.speed_cap, 0.0);
  ASSERT_EQ(sup.faults().size(), 1u);
  EXPECT_EQ(sup.faults()[0].source, "pose");
  EXPECT_EQ(sup.faults()[0].action, "controlled stop");
  EXPECT_NEAR(sup.faults()[0].t, last_pose + 0.2, 0.02);
  // The stop is latched even if the pose comes back; Emergency once standing.
  feed_all(sup, 2.0, AsState::Driving);
  EXPECT_TRUE(sup.evaluate(2.0, 0.0, false).controlled_stop);
  feed_all(sup, 2.6, AsState::Driving);
  EXPECT_EQ(sup.evaluate(2.6, 0.0, false).request, AsRequest::Emergency);
  EXPECT_EQ(sup.faults().size(), 1u);  // logged once
}

TEST(AsSupervisor, NoPlanForTooLongStops) {
  AsSupervisor sup;
  sup.set_mission(Mission::Trackdrive);
  feed_all(sup, 0.0, AsState::Driving);
  Supervision d;
  for (double t = 0.01; t < 0.8; t += 0.01) {
    sup.on_vcu(vcu(t, AsState::Driving));
    sup.heartbeat(InputStream::Pose, t);
    sup.heartbeat(InputStream::Lidar, t);
    sup.on_plan(t, false);  // the planner runs but finds nothing
    d = sup.evaluate(t, 5.0, false);
    if (t < 0.5 - 1e-9) {
      EXPECT_TRUE(d.may_move) << t;
    }
  }
  EXPECT_TRUE(d.controlled_stop);
  EXPECT_EQ(sup.faults().back().source, "planning");
}

TEST(AsSupervisor, BriefLidarLossSlowsAndRecovers) {
  AsSupervisor sup;
  sup.set_mission(Mission::Trackdrive);
  Supervision d;
  for (double t = 0; t < 5.0; t += 0.01) {
    sup.on_vcu(vcu(t, AsState::Driving));
    sup.heartbeat(InputStream::Pose, t);
    sup.on_plan(t, true);
    const bool lost = t > 2.0 && t < 3.0;  // 1 s without detections
    if (!lost) sup.heartbeat(InputStream::Lidar, t);
    d = sup.evaluate(t, 5.0, false);
    ASSERT_TRUE(d.may_move) << t;
    if (t > 2.35 && t < 2.99) {
      EXPECT_DOUBLE_EQ(d.speed_cap, sup.config().degraded_speed) << t;
    }
    if (t > 3.05) {
      EXPECT_GT(d.speed_cap, 100.0) << t;
    }
  }
  ASSERT_EQ(sup.faults().size(), 1u);
  EXPECT_EQ(sup.faults()[0].source, "lidar");
  EXPECT_NE(sup.faults()[0].action.find("slow down"), std::string::npos);
}

TEST(AsSupervisor, ALostCameraIsAFaultThatClearsAndNeverSlowsTheCar) {
  AsSupervisor sup;
  sup.set_mission(Mission::Trackdrive);
  for (int k = 0; k < 500; ++k) {  // 100 Hz cycles
    const double t = 0.01 * k;
    feed_all(sup, t, t < 1.0 ? AsState::Ready : AsState::Driving);
    // Frames at 20 Hz from 0.5 s (none before: a camera that never sent is not lost), none in [2, 3).
    const bool sending = k >= 50 && !(k >= 200 && k < 300);
    if (sending && k % 5 == 0) sup.heartbeat(InputStream::Camera, t);
    const auto d = sup.evaluate(t, 5.0, false);
    if (t >= 1.0) {
      ASSERT_TRUE(d.may_move) << t;
      EXPECT_GT(d.speed_cap, 100.0) << t;
    }
  }
  ASSERT_EQ(sup.faults().size(), 1u);
  const Fault& f = sup.faults()[0];
  EXPECT_EQ(f.source, "camera");
  EXPECT_EQ(f.action, "LiDAR-only detections, colour from reflectivity");
  // The last frame before the gap at 1.95 s; stale 0.5 s later; back with the frame at 3.00 s.
  EXPECT_NEAR(f.t, 1.95 + sup.config().camera_timeout, 0.015);
  ASSERT_TRUE(f.cleared.has_value());
  EXPECT_NEAR(*f.cleared, 3.0, 0.015);
}

TEST(AsSupervisor, LongLidarLossStops) {
  AsSupervisor sup;
  sup.set_mission(Mission::Trackdrive);
  Supervision d;
  for (double t = 0; t < 4.0; t += 0.01) {
    sup.on_vcu(vcu(t, AsState::Driving));
    sup.heartbeat(InputStream::Pose, t);
    sup.on_plan(t, true);
    if (t < 1.0) sup.heartbeat(InputStream::Lidar, t);
    d = sup.evaluate(t, 3.0, false);
  }
  EXPECT_TRUE(d.controlled_stop);
}

TEST(AsSupervisor, StaleVcuStops) {
  AsSupervisor sup;
  sup.set_mission(Mission::Trackdrive);
  feed_all(sup, 0.0, AsState::Driving);
  sup.heartbeat(InputStream::Pose, 0.5);
  sup.heartbeat(InputStream::Lidar, 0.5);
  sup.on_plan(0.5, true);
  const auto d = sup.evaluate(0.5, 5.0, false);
  EXPECT_TRUE(d.controlled_stop);
  EXPECT_EQ(sup.faults().front().source, "vcu");
}

TEST(AsSupervisor, FinishedOnlyAtStandstillAfterTheFinish) {
  AsSupervisor sup;
  sup.set_mission(Mission::Trackdrive);
  double t = 0;
  auto step = [&](double speed, bool finished) {
    feed_all(sup, t, AsState::Driving);
    const auto d = sup.evaluate(t, speed, finished);
    t += 0.1;
    return d;
  };
  for (int i = 0; i < 10; ++i) EXPECT_EQ(step(0.0, false).request, AsRequest::None);  // standing, not finished
  for (int i = 0; i < 10; ++i) EXPECT_EQ(step(3.0, true).request, AsRequest::None);   // finished, rolling
  EXPECT_EQ(step(0.0, true).request, AsRequest::None);                                // just stopped
  Supervision d;
  for (int i = 0; i < 6; ++i) d = step(0.0, true);
  EXPECT_EQ(d.request, AsRequest::Finished);
  EXPECT_TRUE(sup.faults().empty());
}

// A car that stands in Driving before its finish (its way closed) is stopped after stuck_timeout, with the reason,
// and asks for Emergency; standing after the finish is the Finished request instead, and a mission that needs no
// path (inspection, on its jacks) is not watched.
TEST(AsSupervisor, StandingBeforeTheFinishForTooLongStops) {
  SupervisorConfig config;
  config.stuck_timeout = 5.0;
  AsSupervisor sup(config);
  sup.set_mission(Mission::Acceleration);
  double t = 0;
  Supervision d;
  for (; t < 3.0; t += 0.1) {
    feed_all(sup, t, AsState::Driving);
    d = sup.evaluate(t, 8.0, false);  // driving
  }
  const double stood_at = t;
  for (; t < stood_at + 5.0 - 0.05; t += 0.1) {
    feed_all(sup, t, AsState::Driving);
    d = sup.evaluate(t, 0.0, false);
    ASSERT_TRUE(d.may_move) << t;
  }
  for (; t < stood_at + 5.3; t += 0.1) {
    feed_all(sup, t, AsState::Driving);
    d = sup.evaluate(t, 0.0, false);
  }
  EXPECT_TRUE(d.controlled_stop);
  EXPECT_EQ(d.request, AsRequest::Emergency);
  ASSERT_EQ(sup.faults().size(), 1u);
  EXPECT_EQ(sup.faults()[0].source, "mission");
  EXPECT_EQ(sup.faults()[0].what, "standing for 5.00 s before the finish");

  // After the finish the same standstill is the end of the mission.
  AsSupervisor done(config);
  done.set_mission(Mission::Acceleration);
  for (t = 0; t < 20.0; t += 0.1) {
    feed_all(done, t, AsState::Driving);
    d = done.evaluate(t, 0.0, true);
  }
  EXPECT_EQ(d.request, AsRequest::Finished);
  EXPECT_TRUE(done.faults().empty());

  // Inspection needs no path: the car stands on its jacks as long as the sweep lasts.
  AsSupervisor jacks(config);
  jacks.set_mission(Mission::Inspection);
  jacks.require(InputStream::Plan, false);
  for (t = 0; t < 20.0; t += 0.1) {
    feed_all(jacks, t, AsState::Driving);
    d = jacks.evaluate(t, 0.0, false);
  }
  EXPECT_TRUE(d.may_move);
  EXPECT_TRUE(jacks.faults().empty());
}

TEST(AsSupervisor, MissionFaultsAreLoggedOncePerOnset) {
  AsSupervisor sup;
  sup.report(1.0, "gnss", "fix lost", "fallback to real-time planning");
  sup.report(1.1, "gnss", "fix lost", "fallback to real-time planning");
  sup.report(2.0, "gnss", "fix lost", "", false);
  sup.report(3.0, "gnss", "fix lost", "fallback to real-time planning");
  ASSERT_EQ(sup.faults().size(), 2u);
  EXPECT_DOUBLE_EQ(sup.faults()[0].t, 1.0);
  EXPECT_DOUBLE_EQ(sup.faults()[1].t, 3.0);
}

// A stack (re)started beside a VCU already in AS Emergency (its EBS fired when the stack's heartbeat stopped): the
// cause is named from the Status fault bits, nothing moves or is asked for, and the fault clears when the ASMS
// brings the VCU back to Off, from where Ready is asked again.
TEST(AsSupervisor, AVcuInEmergencyAtStartIsAFaultNamingItsCauseUntilAsOff) {
  AsSupervisor sup;
  sup.set_mission(Mission::Trackdrive);
  VcuStatus e = vcu(0.0, AsState::Emergency);
  e.faults = wire::vcu::kFaultEmergencyHeartbeat;
  for (double t = 0; t < 2; t += 0.1) {
    e.stamp = t;
    sup.on_vcu(e);
    sup.heartbeat(InputStream::Pose, t);
    sup.heartbeat(InputStream::Lidar, t);
    sup.on_plan(t, true);
    const auto d = sup.evaluate(t, 0.0, false);
    EXPECT_FALSE(d.may_move);
    EXPECT_EQ(d.request, AsRequest::None);
  }
  ASSERT_EQ(sup.faults().size(), 1u);
  const Fault& f = sup.faults()[0];
  EXPECT_EQ(f.source, "vcu");
  EXPECT_EQ(f.t, 0.0);
  EXPECT_NE(f.what.find("heartbeat"), std::string::npos) << f.what;
  EXPECT_NE(f.action.find("ASMS"), std::string::npos) << f.action;
  EXPECT_FALSE(f.cleared);
  // The ASMS off: AS Off, the fault over, Ready asked again once standing.
  AsRequest asked = AsRequest::None;
  for (double t = 2; t < 3.5; t += 0.1) {
    feed_all(sup, t, AsState::Off);
    if (const auto r = sup.evaluate(t, 0.0, false).request; r != AsRequest::None) asked = r;
  }
  ASSERT_EQ(sup.faults().size(), 1u);
  ASSERT_TRUE(sup.faults()[0].cleared);
  EXPECT_NEAR(*sup.faults()[0].cleared, 2.0, 1e-9);
  EXPECT_EQ(asked, AsRequest::Ready);
}

TEST(AsSupervisor, EachEmergencyCauseIsNamed) {
  namespace vcu_bits = wire::vcu;
  const std::pair<std::uint32_t, const char*> causes[] = {{vcu_bits::kFaultEmergencyRes, "RES"},
                                                          {vcu_bits::kFaultEmergencyRequest, "request"},
                                                          {vcu_bits::kFaultEmergencyAsms, "ASMS"},
                                                          {0u, "did not name"}};
  for (const auto& [bits, word] : causes) {
    AsSupervisor sup;
    feed_all(sup, 0.0, AsState::Driving);
    VcuStatus e = vcu(0.1, AsState::Emergency);
    e.faults = bits;
    sup.on_vcu(e);
    ASSERT_EQ(sup.faults().size(), 1u) << word;
    EXPECT_NE(sup.faults()[0].what.find(word), std::string::npos) << sup.faults()[0].what;
  }
}

// An AS Emergency this stack asked for is its own fault's doing: not logged again as the VCU's.
TEST(AsSupervisor, AnEmergencyThisStackAskedForIsNotLoggedAgain) {
  AsSupervisor sup;
  feed_all(sup, 0.0, AsState::Driving);
  sup.requested(AsRequest::Emergency);
  VcuStatus e = vcu(0.1, AsState::Emergency);
  e.faults = wire::vcu::kFaultEmergencyRequest;
  sup.on_vcu(e);
  EXPECT_TRUE(sup.faults().empty());
  // The RES pressed meanwhile is not this stack's doing.
  AsSupervisor other;
  feed_all(other, 0.0, AsState::Driving);
  other.requested(AsRequest::Emergency);
  e.faults = wire::vcu::kFaultEmergencyRes;
  other.on_vcu(e);
  EXPECT_EQ(other.faults().size(), 1u);
}

}  // namespace
}  // namespace fsd
