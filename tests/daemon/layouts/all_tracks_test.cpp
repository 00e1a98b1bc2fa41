// Every shared track file, driven end to end by the fsd binary (headless lockstep, truth perception, LiDAR and
// camera off) with the mission its name calls for, judged by the scorecard against the virtual car's truth.
// Trackdrive lap 2 is also held against a friction-limited lap time computed here, from the true cones alone.
// One test per file: ctest runs them as separate processes, in parallel under -j.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <numbers>
#include <set>
#include <string>
#include <vector>

#include <unistd.h>

#include <nlohmann/json.hpp>

#include "tests/daemon/fsd_process.hpp"
#include "tests/daemon/layouts/friction_limited_lap.hpp"
#include "tests/scratch_dir.hpp"
#include "tests/truth_sources.hpp"

namespace fsd {
namespace {

const std::string kTracks = "../shared/tracks/";

// Lap 2 against the issues' figures: CTE RMS ≤ 0.15 m, max ≤ 0.5 m; each loop within 8 % of its friction-limited
// time (issue 31 asks the median within 8 % and the worst within 15 %; here every loop is held to the median's bar).
constexpr double kLap2CteRms = 0.15;
constexpr double kLap2CteMax = 0.5;
constexpr double kLap2Margin = 0.08;

// ---------------------------------------------------------------------------------------------------------------
// Which mission each file is for, by its name. Open layouts (no loop) are driven as trackdrive and count one run.
enum class Kind { Loop, Open, Autocross, Acceleration, EbsTest, Skidpad };

struct TrackCase {
  const char* name;
  Kind kind;
};

const std::vector<TrackCase>& cases() {
  static const std::vector<TrackCase> all = {
      {"amz_fssim_acceleration", Kind::Acceleration},
      {"amz_fssim_skidpad", Kind::Skidpad},
      {"amz_fssim_thin", Kind::Loop},
      {"epfl_21_05_2023", Kind::Loop},
      {"epfl_VSV", Kind::Open},
      {"epfl_VSV_XL", Kind::Open},
      {"epfl_VSV_XS", Kind::Open},
      {"epfl_acceleration", Kind::Acceleration},
      {"epfl_acceleration_4_5m", Kind::Acceleration},
      {"epfl_acceleration_4m", Kind::Acceleration},
      {"epfl_acceleration_5_5m", Kind::Acceleration},
      {"epfl_acceleration_large", Kind::Acceleration},
      {"epfl_autoX_Vaudoise_Sponso", Kind::Autocross},
      {"epfl_ebs_test_fss", Kind::EbsTest},
      {"epfl_fsds_competition_1", Kind::Loop},
      {"epfl_fsds_competition_2", Kind::Loop},
      {"epfl_fsds_competition_3", Kind::Loop},
      {"epfl_fsds_default", Kind::Loop},
      {"epfl_short_skidpad", Kind::Skidpad},
      {"epfl_skidpad", Kind::Skidpad},
      {"epfl_skidpad_minimalist", Kind::Skidpad},
      {"epfl_skidpad_reversed", Kind::Skidpad},
      {"epfl_skidpad_v2", Kind::Skidpad},
      {"epfl_track_1", Kind::Loop},
      {"epfl_track_2", Kind::Loop},
      {"epfl_track_3", Kind::Loop},
      {"epfl_track_4", Kind::Loop},
      {"epfl_track_5", Kind::Loop},
  };
  return all;
}

const char* mission_of(Kind k) {
  switch (k) {
    case Kind::Loop:
    case Kind::Open:
      return "trackdrive";
    case Kind::Autocross:
      return "autocross";
    case Kind::Acceleration:
      return "acceleration";
    case Kind::EbsTest:
      return "ebs_test";
    case Kind::Skidpad:
      return "skidpad";
  }
  return "trackdrive";
}

// ---------------------------------------------------------------------------------------------------------------
// Running the binary.
using test::friction_limited_lap_time;
using test::Limits;
using test::read_cones;
using test::run_fsd;
using test::scratch_path;
using test::TrueCones;

std::string fast_config() {
  const std::string path = scratch_path("fsd_fast_all.json");
  std::ofstream(path) << test::truth_sources();
  return path;
}

// The same with lap 2 on the minimum-curvature line (control.trajectory.line).
std::string racing_config() {
  const std::string path = scratch_path("fsd_racing_all.json");
  std::ofstream(path) << test::truth_sources({{"control", {{"trajectory", {{"line", "min_curvature"}}}}}});
  return path;
}

struct Drive {
  int rc = -1;
  nlohmann::json report;
  std::string log;
};

// `fsd run --sim --headless --until-finished` of a mission on a shared track; its scorecard.
Drive drive(const std::string& track, const std::string& mission, int laps, const std::string& config) {
  Drive d;
  const std::string out = scratch_path(track + "_" + mission + "_" + std::to_string(laps) + "_" +
                                       std::filesystem::path(config).stem().string() + ".json");
  std::remove(out.c_str());
  d.rc = run_fsd("run --sim --headless --until-finished --laps " + std::to_string(laps) + " --config " + config +
                     " --mission " + mission + " --track " + kTracks + track + ".csv --report " + out,
                 &d.log);
  std::ifstream f(out);
  if (f.good()) d.report = nlohmann::json::parse(f, nullptr, false);
  return d;
}

// The mission done clean: finished, stopped after the finish, AS Finished, no cone, exit 0.
void expect_clean_finish(const Drive& d) {
  const auto& r = d.report;
  ASSERT_TRUE(r.is_object()) << d.log;
  EXPECT_EQ(d.rc, 0) << d.log;
  EXPECT_EQ(r["cones_hit"], 0) << d.log;
  EXPECT_TRUE(r["finished"]);
  EXPECT_TRUE(r["stopped_after_finish"]);
  EXPECT_EQ(r["as_state"], "Finished");
}

// ---------------------------------------------------------------------------------------------------------------
class AllTracks : public ::testing::TestWithParam<TrackCase> {};

TEST(AllTracksList, EverySharedFileHasAMission) {
  std::set<std::string> listed, present;
  for (const auto& c : cases()) listed.insert(c.name);
  for (const auto& e : std::filesystem::directory_iterator(kTracks))
    if (e.path().extension() == ".csv") present.insert(e.path().stem().string());
  EXPECT_EQ(listed, present) << "a shared track file was added or removed: map it to its mission here";
}

TEST(AllTracksList, ReferenceLapTimeOfACircleIsHandComputed) {
  // A ring road of radius 20 m, 4 m wide: at μ = 1.2 the car corners at √(1.2·9.81·20) = 15.34 m/s all the way
  // round, 2π·20 m take 8.19 s.
  TrueCones t;
  t.start = {20, 0};
  t.yaw = std::numbers::pi / 2;
  for (int k = 0; k < 60; ++k) {
    const double a = 2 * std::numbers::pi * k / 60;
    t.left.push_back({18 * std::cos(a), 18 * std::sin(a)});
    t.right.push_back({22 * std::cos(a), 22 * std::sin(a)});
  }
  double len = 0;
  const double time = friction_limited_lap_time(t, {1.2, 6, 8, 20}, &len);
  // Cones on 60-gons: the centre line runs a few centimetres inside the circle (about 0.5 % shorter).
  EXPECT_NEAR(len, 2 * std::numbers::pi * 20, 1.0);
  EXPECT_NEAR(time, 2 * std::numbers::pi * 20 / std::sqrt(1.2 * 9.81 * 20), 0.1);
}

TEST_P(AllTracks, CompletesItsMission) {
  const TrackCase c = GetParam();
  const std::string file = kTracks + c.name + ".csv";
  const Drive d = drive(c.name, mission_of(c.kind), 2, fast_config());
  ASSERT_TRUE(d.report.is_object()) << d.log;
  const auto& r = d.report;
  const int rc = d.rc;
  const std::string& log = d.log;
  const auto& laps = r["laps"];
  std::string line = std::string(c.name) + " " + mission_of(c.kind) + ": cones hit " + r["cones_hit"].dump() + ", AS " +
                     r["as_state"].get<std::string>() + ", sim " + r["sim_time_s"].dump() + " s";
  for (const auto& l : laps)
    line += " | lap " + l["lap"].dump() + " " + l["time_s"].dump() + " s, CTE rms " + l["cte_rms_m"].dump() + " max " +
            l["cte_max_m"].dump();
  std::printf("%s\n", line.c_str());

  EXPECT_EQ(r["mission"], mission_of(c.kind));
  EXPECT_EQ(r["cones_hit"], 0);
  EXPECT_TRUE(r["stopped_after_finish"]);
  // The cone map against the world's cones: nothing that is not there, every cone where it is, in its colour
  // (truth perception: 3 cm noise). Every cone is passed within sight except the far end of an acceleration
  // lane's 100 m braking zone, where the car has long stopped.
  const auto& map = r["map"];
  EXPECT_EQ(map["ghosts"], 0);
  EXPECT_LT(map["rmse_m"].get<double>(), 0.02);
  EXPECT_EQ(map["colour_accuracy"], 1.0);
  if (c.kind != Kind::Acceleration && c.kind != Kind::EbsTest) {
    EXPECT_EQ(map["missed"], 0);
  }
  if (c.kind == Kind::EbsTest) {
    // The EBS test ends in AS Emergency by design: the stack triggers the EBS on the straight.
    EXPECT_EQ(r["as_state"], "Emergency");
    EXPECT_TRUE(r["finished"]);
    return;
  }
  EXPECT_EQ(rc, 0) << log;
  EXPECT_TRUE(r["finished"]);
  EXPECT_EQ(r["as_state"], "Finished");
  switch (c.kind) {
    case Kind::Loop:
      ASSERT_EQ(laps.size(), 2u);
      break;
    case Kind::Open:
      EXPECT_EQ(r["layout"], "open");
      ASSERT_EQ(laps.size(), 1u);
      break;
    case Kind::Autocross:
      ASSERT_EQ(laps.size(), 1u);
      break;
    case Kind::Acceleration:
      ASSERT_EQ(laps.size(), 1u);
      // From a standing start ≤ 5 m before the line at a = µg ≈ 11.8 m/s², 75 m take at least 2.6 s.
      EXPECT_GT(laps[0]["time_s"].get<double>(), 2.6);
      // Not slower than its sight allows: it never drives faster than it stops within the lane it has mapped
      // (20 m of sight less up to a 5 m cone spacing, the 2.4 m rear axle to nose and the 1 m margin, braking
      // at 8 m/s² after 0.3 s: 11-14 m/s), which takes 75 m in 5.4-6.8 s, plus the start's build-up.
      EXPECT_LT(laps[0]["time_s"].get<double>(), 7.5);
      break;
    case Kind::Skidpad:
      ASSERT_EQ(laps.size(), 4u);
      // Each circle held as tightly as the issue asks of a trackdrive's lap 2.
      for (const auto& l : laps) {
        EXPECT_LE(l["cte_rms_m"].get<double>(), kLap2CteRms);
        EXPECT_LE(l["cte_max_m"].get<double>(), kLap2CteMax);
      }
      break;
    default:
      break;
  }
  if (c.kind != Kind::Loop) return;

  // Trackdrive lap 2 on the recorded line.
  const auto& l1 = laps[0];
  const auto& l2 = laps[1];
  EXPECT_LE(l2["cte_rms_m"].get<double>(), kLap2CteRms);
  EXPECT_LE(l2["cte_max_m"].get<double>(), kLap2CteMax);
  EXPECT_LE(l2["time_s"].get<double>(), 0.8 * l1["time_s"].get<double>());
  const auto& v = r["vehicle"];
  const Limits lim{v["mu"].get<double>(), v["a_accel_max"].get<double>(), v["a_brake_max"].get<double>(),
                   v["v_max"].get<double>()};
  ASSERT_GT(lim.mu, 0.0);
  const double reference = friction_limited_lap_time(read_cones(file), lim);
  std::printf("%s: lap 2 %.3f s, friction-limited %.3f s (%+.1f %%)\n", c.name, l2["time_s"].get<double>(), reference,
              100.0 * (l2["time_s"].get<double>() / reference - 1.0));
  EXPECT_LE(l2["time_s"].get<double>(), (1.0 + kLap2Margin) * reference);
  // Much faster than the friction limit would mean the reference or the timing is wrong.
  EXPECT_GE(l2["time_s"].get<double>(), 0.85 * reference);

  // The minimum-curvature option: the same two laps clean, lap 2 faster than on the centre line.
  const Drive race = drive(c.name, "trackdrive", 2, racing_config());
  expect_clean_finish(race);
  ASSERT_EQ(race.report["laps"].size(), 2u);
  const double race2 = race.report["laps"][1]["time_s"].get<double>();
  std::printf("%s: lap 2 on the min-curvature line %.3f s (%+.1f %% on the centre line's)\n", c.name, race2,
              100.0 * (race2 / l2["time_s"].get<double>() - 1.0));
  // At least 1 % faster, unless the centre line's lap is already within a per cent or two of its friction limit:
  // then the line alone has no such margin left, and it need only reach that limit.
  EXPECT_LE(race2, std::max(0.99 * l2["time_s"].get<double>(), 1.02 * reference));
}

std::string case_name(const ::testing::TestParamInfo<TrackCase>& info) { return info.param.name; }

INSTANTIATE_TEST_SUITE_P(SharedTracks, AllTracks, ::testing::ValuesIn(cases()), case_name);

TEST(AllTracksTight, TenLapsAsAtFormulaStudentGermany) {
  // FSG's trackdrive is 10 laps (the paper's FSAC had 2). Laps 3–10 run on the same recorded line as lap 2: each
  // as clean as lap 2 (the CTE figures) and within 1 % of its time, then the stop after the tenth.
  const Drive d = drive("epfl_track_1", "trackdrive", 10, fast_config());
  expect_clean_finish(d);
  const auto& laps = d.report["laps"];
  ASSERT_EQ(laps.size(), 10u);
  const double lap2 = laps[1]["time_s"].get<double>();
  for (std::size_t i = 1; i < laps.size(); ++i) {
    EXPECT_NEAR(laps[i]["time_s"].get<double>(), lap2, 0.01 * lap2) << "lap " << i + 1;
    EXPECT_LE(laps[i]["cte_rms_m"].get<double>(), kLap2CteRms) << "lap " << i + 1;
    EXPECT_LE(laps[i]["cte_max_m"].get<double>(), kLap2CteMax) << "lap " << i + 1;
  }
}

TEST(AllTracksTight, TheAutocrossLayoutDrivenAsATwoLapTrackdrive) {
  // The issue asks for every shared trackdrive/autocross layout with --laps 2 to finish clean. This one has the
  // rules' tightest hairpin with an S straight out of it: on lap 2's recorded line, at lap 2's speeds, the line
  // through the hairpin must be shaped to the car as on lap 1, and driven at that line's cap. Only cones, the
  // finish and the stop are asserted: the layout is an autocross one, all corners, and lap 2 gains ~13 %, not 20.
  // The same on the minimum-curvature line.
  for (const std::string& config : {fast_config(), racing_config()}) {
    const Drive d = drive("epfl_autoX_Vaudoise_Sponso", "trackdrive", 2, config);
    expect_clean_finish(d);
    ASSERT_EQ(d.report["laps"].size(), 2u) << config;
    EXPECT_LT(d.report["laps"][1]["time_s"].get<double>(), d.report["laps"][0]["time_s"].get<double>()) << config;
  }
}

}  // namespace
}  // namespace fsd
