// The scorecard measured on a hand-made drive: along the true centre line of epfl_track_1 at a constant 5 m/s,
// offset laterally by a known amount, two laps and a stop.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "daemon/scoring/scorecard.hpp"

namespace fsd {
namespace {

TEST(Scorecard, LapsCrossTrackErrorAndStopOnAHandMadeDrive) {
  const Track track = load_track("../shared/tracks/epfl_track_1.csv");
  const sim::ReferenceLine ref(track);
  Scorecard card(track, Mission::Trackdrive, 2, 30.0, 7);
  const auto& pts = ref.points();
  const double v = 5.0, offset = 0.2;
  sim::VehicleTruth truth;
  truth.t = 0;
  double s = 0;
  // Drive the centre line from its first point, offset 0.2 m left, until 10 m past the finish.
  const std::size_t n = pts.size();
  std::size_t after_finish = 0;
  for (std::size_t k = 0; k < 4 * n && after_finish < 40; ++k) {
    if (card.finished()) ++after_finish;
    const Vec2 a = pts[k % n], b = pts[(k + 1) % n];
    const Vec2 dir = (b - a).normalized();
    const Vec2 left(-dir.y(), dir.x());
    truth.pose = {a.x() + offset * left.x(), a.y() + offset * left.y(), std::atan2(dir.y(), dir.x())};
    truth.vx = v;
    card.on_truth(truth);
    const double ds = (b - a).norm();
    s += ds;
    truth.t += ds / v;
  }
  // Stand still where the drive ended (just past the finish line).
  truth.vx = 0;
  card.on_truth(truth);
  card.set_as_state(AsState::Finished);

  ASSERT_EQ(card.laps_completed(), 2);
  const double lap_time = ref.length() / v;
  for (const auto& lap : card.laps()) {
    EXPECT_NEAR(lap.time_s, lap_time, 0.2);
    EXPECT_NEAR(lap.cte_rms_m, offset, 0.02);  // the centre line is sampled every 0.25 m
    EXPECT_LT(lap.cte_max_m, offset + 0.05);
    EXPECT_NEAR(lap.v_max_m_s, v, 1e-9);
  }
  EXPECT_TRUE(card.finished());
  EXPECT_TRUE(card.stopped_after_finish());
  EXPECT_TRUE(card.mission_succeeded());
  const auto j = card.to_json();
  EXPECT_EQ(j["track"], "epfl_track_1");
  EXPECT_EQ(j["mission"], "trackdrive");
  EXPECT_EQ(j["as_state"], "Finished");
  EXPECT_EQ(j["laps"].size(), 2u);
  for (const char* key : {"seed", "finished", "stopped_after_finish", "sim_time_s", "wall_time_s", "cones_hit", "laps",
                          "latency_ms", "faults", "vehicle"})
    EXPECT_TRUE(j.contains(key)) << key;
}

TEST(Scorecard, AStartPastTheLineTimesLapOneFromTheFirstMotion) {
  // epfl_21_05_2023's car stands just past its timing line. It waits 6 s (Ready, the RES go), then drives the
  // centre line from where it stands at 5 m/s: lap 1 is the drive back to the line, not the drive plus the wait.
  const Track track = load_track("../shared/tracks/epfl_21_05_2023.csv");
  const sim::ReferenceLine ref(track);
  Scorecard card(track, Mission::Trackdrive, 1, 30.0, 1);
  const auto& pts = ref.points();
  const std::size_t n = pts.size();
  std::size_t k0 = 0;
  for (std::size_t k = 0; k < n; ++k)
    if ((pts[k] - track.start.position()).norm() < (pts[k0] - track.start.position()).norm()) k0 = k;
  const double v = 5.0;
  sim::VehicleTruth truth;
  truth.pose = track.start;
  for (truth.t = 0; truth.t < 6.0; truth.t += 0.01) card.on_truth(truth);  // standing
  double driven = 0;
  for (std::size_t k = k0; k < k0 + 2 * n && !card.finished(); ++k) {
    const Vec2 a = pts[k % n], b = pts[(k + 1) % n];
    const Vec2 dir = (b - a).normalized();
    truth.pose = {a.x(), a.y(), std::atan2(dir.y(), dir.x())};
    truth.vx = v;
    card.on_truth(truth);
    driven += (b - a).norm();
    truth.t += (b - a).norm() / v;
  }
  ASSERT_EQ(card.laps_completed(), 1);
  // Timed from t = 6 s: the line lies less than 10 m behind the start (what counts as starting past it), so
  // the lap is a little under one length of driving; with the wait it would be 6 s over.
  EXPECT_LT(card.laps()[0].time_s, ref.length() / v);
  EXPECT_GT(card.laps()[0].time_s, (ref.length() - 10.0) / v);
  EXPECT_LT(card.laps()[0].time_s, driven / v + 0.1);
}

TEST(Scorecard, SkidPadCrossTrackErrorIsMeasuredFromItsCircles) {
  // epfl_skidpad: start at the origin heading +y, the timing line at y = 15, the right circle's centre at
  // (9.125, 15), the left one's at (-9.125, 15) (18.25 m driving diameter, the rules'). Drive 0.3 m outside
  // the right circle once round, clockwise from the crossing: one lap with a CTE of 0.3 m all the way.
  const Track track = load_track("../shared/tracks/epfl_skidpad.csv");
  Scorecard card(track, Mission::Skidpad, 4, 25.0, 1);
  sim::VehicleTruth truth;
  truth.vx = 5.0;
  const Vec2 c(9.125, 15.0);
  const double r = 9.125 + 0.3;
  // Up the entry axis to just before the line, then round the circle (starting at angle π, going clockwise).
  for (double y = 5.0; y < 14.99; y += 0.5) {
    truth.pose = {0.0, y, 1.5707963};
    card.on_truth(truth);
    truth.t += 0.1;
  }
  for (int k = 0; k <= 2 * 400; ++k) {  // twice round: the second crossing ends lap 1
    const double a = 3.14159265 - 2 * 3.14159265 * k / 400.0;
    truth.pose = {c.x() + r * std::cos(a), c.y() + r * std::sin(a), a - 1.5707963};
    card.on_truth(truth);
    truth.t += 0.02;
  }
  ASSERT_GE(card.laps().size(), 1u);
  EXPECT_NEAR(card.laps()[0].cte_rms_m, 0.3, 0.02);
  EXPECT_NEAR(card.laps()[0].cte_max_m, 0.3, 0.02);
}

TEST(Scorecard, HitConeOrNoStopFailsTheMission) {
  const Track track = load_track("../shared/tracks/epfl_acceleration.csv");
  Scorecard card(track, Mission::Acceleration, 1, 100.0, 1);
  sim::VehicleTruth t;
  t.pose = {0, 0, M_PI / 2};
  t.vx = 10;
  for (int k = 0; k <= 2000; ++k) {  // straight up the centre at 10 m/s, 200 m: past the 100 m stop zone
    t.t = k * 0.01;
    t.pose.y = k * 0.1;
    card.on_truth(t);
  }
  EXPECT_EQ(card.laps_completed(), 1);
  EXPECT_NEAR(card.laps()[0].time_s, 7.5, 0.02);  // 75 m between the gates at 10 m/s
  EXPECT_TRUE(card.finished());
  EXPECT_FALSE(card.stopped_after_finish());
  EXPECT_FALSE(card.mission_succeeded());
}

}  // namespace
}  // namespace fsd
