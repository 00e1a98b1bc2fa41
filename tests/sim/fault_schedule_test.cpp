// The virtual car's fault schedule: triggers by time and by lap (the timekeeper's gates of a shared track), and
// what each fault does to the bytes the car sends and receives.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "common/wire/vcu_protocol.hpp"
#include "drivers/sim/fault_schedule.hpp"
#include "drivers/sim/virtual_car.hpp"

namespace fsd::sim {
namespace {

TEST(FaultSchedule, EveryFaultIsOffByDefaultAndDocumented) {
  ConfigSchema schema;
  describe_fault_schedule(schema);
  const Config cfg(std::make_shared<const ConfigSchema>(schema));
  const FaultScheduleConfig c = read_fault_schedule(cfg);
  for (const FaultKind k : kFaultKinds) {
    EXPECT_FALSE(c.trigger(k).enabled()) << to_string(k);
    for (const char* key : {"lap", "at_s", "duration_s"}) {
      const auto* e = schema.find("sim.faults." + std::string(to_string(k)) + "." + key);
      ASSERT_NE(e, nullptr) << to_string(k) << "." << key;
      EXPECT_FALSE(e->doc.empty());
    }
  }
  EXPECT_EQ(c.gnss.mode, "no_fix");
  const FaultSchedule s(c, load_track("../shared/tracks/epfl_track_1.csv"));
  EXPECT_FALSE(s.any_enabled());
  EXPECT_FALSE(s.active(FaultKind::Lidar, 10.0));
}

TEST(FaultSchedule, TimeTriggerOpensAndClosesItsWindow) {
  FaultScheduleConfig c;
  c.lidar = {0, 12.0, 1.0};
  c.vcu_link = {0, 3.0, 0.0};  // open-ended
  const FaultSchedule s(c, load_track("../shared/tracks/epfl_track_1.csv"));
  EXPECT_FALSE(s.active(FaultKind::Lidar, 11.99));
  EXPECT_TRUE(s.active(FaultKind::Lidar, 12.0));
  EXPECT_TRUE(s.active(FaultKind::Lidar, 12.99));
  EXPECT_FALSE(s.active(FaultKind::Lidar, 13.0));
  EXPECT_FALSE(s.active(FaultKind::VcuLink, 2.99));
  EXPECT_TRUE(s.active(FaultKind::VcuLink, 1e5));
  EXPECT_FALSE(s.active(FaultKind::Gnss, 12.5));
}

TEST(FaultSchedule, LapTriggerWaitsForThatLapByTheGates) {
  // epfl_track_1: the timing line is at y = 6 across x ∈ [-2.2, 2.2]; the car starts at the origin heading +y.
  FaultScheduleConfig c;
  c.gnss.lap = 2;
  c.gnss.at_s = 3.0;
  c.gnss.duration_s = 5.0;
  c.planner_stall = {1, 0.5, 0.0};
  FaultSchedule s(c, load_track("../shared/tracks/epfl_track_1.csv"));
  s.on_truth(0.0, {0.0, 0.0});
  s.on_truth(1.0, {0.0, 5.0});
  EXPECT_FALSE(s.window(FaultKind::PlannerStall));
  s.on_truth(1.2, {0.0, 7.0});  // crosses y = 6 at t = 1.1: lap 1 begins
  ASSERT_EQ(s.lap_starts().size(), 1u);
  EXPECT_NEAR(s.lap_starts()[0], 1.1, 1e-9);
  ASSERT_TRUE(s.window(FaultKind::PlannerStall));
  EXPECT_NEAR(s.window(FaultKind::PlannerStall)->start, 1.6, 1e-9);
  EXPECT_TRUE(std::isinf(s.window(FaultKind::PlannerStall)->end));
  EXPECT_FALSE(s.window(FaultKind::Gnss));
  // Around the loop: moving backwards over the line or beside the gate is no crossing.
  s.on_truth(30.0, {0.0, 5.0});
  s.on_truth(30.5, {10.0, 7.0});
  EXPECT_FALSE(s.window(FaultKind::Gnss));
  s.on_truth(40.0, {0.0, 5.0});
  s.on_truth(40.4, {0.0, 9.0});  // crosses at t = 40.1: lap 2 begins
  const auto w = s.window(FaultKind::Gnss);
  ASSERT_TRUE(w);
  EXPECT_NEAR(w->start, 43.1, 1e-9);
  EXPECT_NEAR(w->end, 48.1, 1e-9);
  EXPECT_TRUE(s.active(FaultKind::Gnss, 45.0));
  EXPECT_FALSE(s.active(FaultKind::Gnss, 48.2));
}

// A virtual car on epfl_track_1 with byte counters on its sinks.
struct CarBench {
  std::vector<Stamp> lidar_packets, gnss_bytes, statuses, camera_frames;
  std::vector<int> gga_quality;
  std::unique_ptr<VirtualCar> car;

  explicit CarBench(VirtualCarSettings s) {
    SensorSinks sinks;
    sinks.camera = [this](Stamp t, std::span<const std::uint8_t>) { camera_frames.push_back(t); };
    sinks.lidar = [this](Stamp t, std::span<const std::uint8_t>) { lidar_packets.push_back(t); };
    sinks.gnss = [this](Stamp t, std::span<const std::uint8_t> b) {
      gnss_bytes.push_back(t);
      const std::string text(b.begin(), b.end());
      // $GNGGA,hhmmss.ss,lat,N,lon,E,quality,...: the seventh field.
      if (text.size() > 6 && text.compare(3, 3, "GGA") == 0) {
        std::size_t p = 0;
        for (int i = 0; i < 6; ++i) p = text.find(',', p) + 1;
        gga_quality.push_back(text[p] - '0');
      }
    };
    sinks.vcu_status = [this](Stamp t, std::span<const std::uint8_t>) { statuses.push_back(t); };
    car = std::make_unique<VirtualCar>(load_track("../shared/tracks/epfl_track_1.csv"), s, 1, sinks);
  }
  static std::size_t count(const std::vector<Stamp>& v, Stamp a, Stamp b) {
    std::size_t n = 0;
    for (const Stamp t : v) n += (t >= a && t < b);
    return n;
  }
};

TEST(FaultSchedule, LidarOutageSilencesTheVlp16AndOnlyIt) {
  VirtualCarSettings s;
  s.run.lidar = true;
  s.run.camera = false;
  s.faults.lidar = {0, 0.5, 0.4};
  CarBench b(s);
  b.car->advance_to(1.3);
  // 754 packets/s: ~226 in each 0.3 s before and after, none in the window.
  EXPECT_NEAR(static_cast<double>(CarBench::count(b.lidar_packets, 0.1, 0.4)), 226.0, 2.0);
  EXPECT_EQ(CarBench::count(b.lidar_packets, 0.5, 0.9), 0u);
  EXPECT_NEAR(static_cast<double>(CarBench::count(b.lidar_packets, 0.95, 1.25)), 226.0, 2.0);
  EXPECT_GT(CarBench::count(b.gnss_bytes, 0.5, 0.9), 0u);  // the GNSS-INS is not affected
}

TEST(FaultSchedule, CameraOutageSilencesTheCameraAndOnlyIt) {
  VirtualCarSettings s;
  s.run.lidar = true;
  s.run.camera = true;
  s.faults.camera = {0, 0.5, 0.4};
  CarBench b(s);
  b.car->advance_to(1.3);
  // 20 frames/s: 6 in each 0.3 s before and after, none sent in the window; the LiDAR goes on.
  EXPECT_EQ(CarBench::count(b.camera_frames, 0.1, 0.4), 6u);
  EXPECT_EQ(CarBench::count(b.camera_frames, 0.5, 0.9), 0u);
  EXPECT_EQ(CarBench::count(b.camera_frames, 0.95, 1.25), 6u);
  EXPECT_NEAR(static_cast<double>(CarBench::count(b.lidar_packets, 0.5, 0.9)), 302.0, 2.0);
}

TEST(FaultSchedule, GnssOutageReportsNoFixOrNothing) {
  for (const std::string mode : {"no_fix", "silent"}) {
    SCOPED_TRACE(mode);
    VirtualCarSettings s;
    s.run.camera = false;
    s.run.lidar = false;
    s.faults.gnss.at_s = 1.0;
    s.faults.gnss.duration_s = 1.0;
    s.faults.gnss.mode = mode;
    CarBench b(s);
    std::vector<int> before, during, after;
    std::size_t seen = 0;
    auto take = [&](std::vector<int>& into, Stamp until) {
      b.car->advance_to(until);
      into.assign(b.gga_quality.begin() + static_cast<long>(seen), b.gga_quality.end());
      seen = b.gga_quality.size();
    };
    // A GGA leaves the receiver 10 ms after its epoch (plus < 1 ms on the line): split between deliveries.
    take(before, 1.005);
    take(during, 2.005);
    take(after, 3.0);
    EXPECT_EQ(before.size(), 50u);         // 50 Hz epochs at t = 0 … 0.98
    for (int q : before) EXPECT_EQ(q, 4);  // RTK
    if (mode == "no_fix") {
      EXPECT_EQ(during.size(), 50u);
      for (int q : during) EXPECT_EQ(q, 0);
    } else {
      EXPECT_TRUE(during.empty());
    }
    ASSERT_FALSE(after.empty());
    for (int q : after) EXPECT_EQ(q, 4);
  }
}

TEST(FaultSchedule, VcuLinkCutFiresTheStandinsEbsWithin100ms) {
  VirtualCarSettings s;
  s.run.camera = false;
  s.run.lidar = false;
  s.vcu.ready_to_drive_s = 0.0;
  s.vcu.res_go_at_s = 0.0;  // go as soon as Ready
  s.faults.vcu_link = {0, 3.0, 0.0};
  CarBench b(s);
  wire::vcu::Sequencer seq;
  wire::vcu::Command cmd;
  cmd.mission = Mission::Trackdrive;
  cmd.as_request = wire::vcu::AsRequest::Ready;
  cmd.target_speed = 4.0;
  double speed_at_cut = 0;
  for (int k = 1; k <= 500; ++k) {  // a stack at 100 Hz for 5 s
    const Stamp t = k * 0.01;
    b.car->advance_to(t);
    if (std::abs(t - 3.0) < 1e-9) speed_at_cut = b.car->truth().speed();
    b.car->feed_vcu(t, wire::vcu::encode(cmd, seq.next()));
  }
  EXPECT_GT(speed_at_cut, 3.0);
  // The last Command arrived at 2.99 s; the heartbeat timeout is 0.1 s.
  Stamp emergency = -1;
  for (const auto& tr : b.car->vcu().transitions())
    if (tr.to == AsState::Emergency) emergency = tr.t;
  EXPECT_GT(emergency, 3.09 - 1e-9);
  EXPECT_LT(emergency, 3.10);
  EXPECT_TRUE(b.car->vcu().output().ebs);
  EXPECT_LT(b.car->truth().speed(), 0.05);
  // Status frames stop reaching the daemon at the cut (100 Hz before it).
  EXPECT_GE(CarBench::count(b.statuses, 2.0, 3.0), 99u);
  EXPECT_EQ(CarBench::count(b.statuses, 3.0, 5.0), 0u);
}

}  // namespace
}  // namespace fsd::sim
