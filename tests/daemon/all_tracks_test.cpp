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
#include "tests/daemon/track_csv.hpp"
#include "tests/scratch_dir.hpp"

namespace fsd {
namespace {

const std::string kTracks = "../shared/tracks/";

// Lap 2 against the issue's figures: CTE RMS ≤ 0.15 m, max ≤ 0.5 m, within 5 % of the friction-limited time.
constexpr double kLap2CteRms = 0.15;
constexpr double kLap2CteMax = 0.5;
constexpr double kLap2Margin = 0.05;

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
    case Kind::Open: return "trackdrive";
    case Kind::Autocross: return "autocross";
    case Kind::Acceleration: return "acceleration";
    case Kind::EbsTest: return "ebs_test";
    case Kind::Skidpad: return "skidpad";
  }
  return "trackdrive";
}

// ---------------------------------------------------------------------------------------------------------------
// Running the binary.
using test::run_fsd;
using test::scratch_path;

std::string fast_config() {
  const std::string path = scratch_path("fsd_fast_all.json");
  std::ofstream(path) << R"({"sim": {"enable_camera": false, "enable_lidar": false}})";
  return path;
}

// The same with lap 2 on the minimum-curvature line (control.trajectory.line).
std::string racing_config() {
  const std::string path = scratch_path("fsd_racing_all.json");
  std::ofstream(path) << R"({"sim": {"enable_camera": false, "enable_lidar": false},
                             "control": {"trajectory": {"line": "min_curvature"}}})";
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
// The friction-limited lap time of the true centre line, from the track file only (no fsd code).
struct P2 {
  double x = 0, y = 0;
};
P2 operator+(P2 a, P2 b) { return {a.x + b.x, a.y + b.y}; }
P2 operator-(P2 a, P2 b) { return {a.x - b.x, a.y - b.y}; }
P2 operator*(double k, P2 a) { return {k * a.x, k * a.y}; }
double norm(P2 a) { return std::hypot(a.x, a.y); }
double dot(P2 a, P2 b) { return a.x * b.x + a.y * b.y; }

struct TrueCones {
  P2 start;
  double yaw = 0;
  std::vector<P2> left, right;
};

TrueCones read_cones(const std::string& file) {
  TrueCones t;
  for (const auto& r : test::read_track_csv(file)) {
    const P2 p{r.x, r.y};
    if (r.tag == "blue") t.left.push_back(p);
    else if (r.tag == "yellow") t.right.push_back(p);
    else if (r.tag == "car_start") t.start = p, t.yaw = r.direction;
  }
  return t;
}

// Boundary cones of a loop in driving order: from the cone nearest the start (not behind it), first step
// forwards, then always the nearest cone not yet taken; then untangled.
std::vector<P2> order_boundary(std::vector<P2> pts, P2 start, double yaw) {
  const P2 fwd{std::cos(yaw), std::sin(yaw)};
  std::vector<P2> out;
  std::size_t first = 0;
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const double c = norm(pts[i] - start) + (dot(pts[i] - start, fwd) < -1.0 ? 100.0 : 0.0);
    if (c < best) best = c, first = i;
  }
  out.push_back(pts[first]);
  pts.erase(pts.begin() + static_cast<long>(first));
  while (!pts.empty()) {
    std::size_t pick = 0;
    double pc = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < pts.size(); ++i) {
      double c = norm(pts[i] - out.back());
      if (out.size() == 1 && dot(pts[i] - out.back(), fwd) < 0) c += 1000.0;
      if (c < pc) pc = c, pick = i;
    }
    out.push_back(pts[pick]);
    pts.erase(pts.begin() + static_cast<long>(pick));
  }
  // The greedy order can jump across a narrow island (amz_fssim_thin) and come back later: shorten the loop by
  // reversing stretches (2-opt) until no reversal helps, keeping the first cone first and the driving direction.
  const std::size_t n = out.size();
  for (bool again = n >= 5; again;) {
    again = false;
    for (std::size_t i = 1; i + 1 < n; ++i)
      for (std::size_t j = i + 1; j < n; ++j) {
        const std::size_t k = (j + 1) % n;
        if (k == i - 1) continue;
        if (norm(out[i - 1] - out[j]) + norm(out[i] - out[k]) < norm(out[i - 1] - out[i]) + norm(out[j] - out[k]) - 1e-9) {
          std::reverse(out.begin() + static_cast<long>(i), out.begin() + static_cast<long>(j) + 1);
          again = true;
        }
      }
  }
  if (n >= 2 && dot(out[1] - out[0], fwd) < 0) std::reverse(out.begin() + 1, out.end());
  return out;
}

// A closed polyline resampled at (about) spacing ds.
std::vector<P2> resample_loop(const std::vector<P2>& poly, double ds) {
  std::vector<double> s{0};
  for (std::size_t i = 1; i <= poly.size(); ++i) s.push_back(s.back() + norm(poly[i % poly.size()] - poly[i - 1]));
  const double len = s.back();
  const auto n = static_cast<std::size_t>(std::round(len / ds));
  std::vector<P2> out;
  std::size_t seg = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const double q = len * static_cast<double>(k) / static_cast<double>(n);
    while (s[seg + 1] < q) ++seg;
    const double f = (q - s[seg]) / std::max(1e-12, s[seg + 1] - s[seg]);
    out.push_back(poly[seg] + f * (poly[(seg + 1) % poly.size()] - poly[seg]));
  }
  return out;
}

P2 closest_on_loop(const std::vector<P2>& poly, P2 p) {
  P2 best = poly.front();
  double bd = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const P2 a = poly[i], b = poly[(i + 1) % poly.size()];
    const double l2 = dot(b - a, b - a);
    const double f = l2 > 0 ? std::clamp(dot(p - a, b - a) / l2, 0.0, 1.0) : 0.0;
    const P2 q = a + f * (b - a);
    if (norm(p - q) < bd) bd = norm(p - q), best = q;
  }
  return best;
}

struct Limits {
  double mu, a_accel, a_brake, v_max;
};

// Centre line: midpoints of the left boundary's samples and their closest right-boundary points, resampled at
// 0.5 m and smoothed by a ±2 m moving average (the cones' placement ripple is no part of the track's shape).
// Curvature: the circle through the points 2 m before and after. Speed: min(√(μg/|κ|), v_max), then a periodic
// forward–backward pass under the friction circle with the traction and brake limits. Time: Σ ds / v̄.
double friction_limited_lap_time(const TrueCones& t, const Limits& lim, double* length = nullptr) {
  constexpr double g = 9.81, ds = 0.5;
  const auto left = resample_loop(order_boundary(t.left, t.start, t.yaw), 0.25);
  const auto right = order_boundary(t.right, t.start, t.yaw);
  std::vector<P2> mid;
  for (const P2& p : left) mid.push_back(0.5 * (p + closest_on_loop(right, p)));
  auto line = resample_loop(mid, ds);
  for (int pass = 0; pass < 2; ++pass) {
    const std::size_t n = line.size();  // each resampling may change the count
    std::vector<P2> sm(n);
    for (std::size_t i = 0; i < n; ++i) {
      P2 acc;
      for (int k = -4; k <= 4; ++k) acc = acc + line[(i + n + static_cast<std::size_t>(k + 4) - 4) % n];
      sm[i] = (1.0 / 9.0) * acc;
    }
    line = resample_loop(sm, ds);
  }
  const std::size_t m = line.size();
  std::vector<double> v(m), seg(m), kappa(m);
  for (std::size_t i = 0; i < m; ++i) {
    const P2 a = line[(i + m - 4) % m], b = line[i], c = line[(i + 4) % m];
    const double cross = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
    kappa[i] = 2.0 * std::abs(cross) / std::max(1e-9, norm(b - a) * norm(c - b) * norm(c - a));
    v[i] = kappa[i] < 1e-9 ? lim.v_max : std::min(lim.v_max, std::sqrt(lim.mu * g / kappa[i]));
    seg[i] = norm(line[(i + 1) % m] - line[i]);
  }
  auto grip_left = [&](double speed, std::size_t i) {
    const double ay = speed * speed * kappa[i];
    const double total = lim.mu * g;
    return ay >= total ? 0.0 : std::sqrt(total * total - ay * ay);
  };
  const auto slowest = static_cast<std::size_t>(std::min_element(v.begin(), v.end()) - v.begin());
  for (int round = 0; round < 2; ++round) {
    for (std::size_t k = 0; k < m; ++k) {
      const std::size_t i = (slowest + k) % m, j = (i + 1) % m;
      const double a = std::min(lim.a_accel, grip_left(v[i], i));
      v[j] = std::min(v[j], std::sqrt(v[i] * v[i] + 2 * a * seg[i]));
    }
    for (std::size_t k = 0; k < m; ++k) {
      const std::size_t j = (slowest + m - k) % m, i = (j + m - 1) % m;
      const double a = std::min(lim.a_brake, grip_left(v[j], j));
      v[i] = std::min(v[i], std::sqrt(v[j] * v[j] + 2 * a * seg[i]));
    }
  }
  double time = 0, len = 0;
  for (std::size_t i = 0; i < m; ++i) {
    time += seg[i] / (0.5 * (v[i] + v[(i + 1) % m]));
    len += seg[i];
  }
  if (length) *length = len;
  return time;
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
  std::string line = std::string(c.name) + " " + mission_of(c.kind) + ": cones hit " + r["cones_hit"].dump() +
                     ", AS " + r["as_state"].get<std::string>() + ", sim " + r["sim_time_s"].dump() + " s";
  for (const auto& l : laps)
    line += " | lap " + l["lap"].dump() + " " + l["time_s"].dump() + " s, CTE rms " + l["cte_rms_m"].dump() +
            " max " + l["cte_max_m"].dump();
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
    case Kind::Loop: ASSERT_EQ(laps.size(), 2u); break;
    case Kind::Open:
      EXPECT_EQ(r["layout"], "open");
      ASSERT_EQ(laps.size(), 1u);
      break;
    case Kind::Autocross: ASSERT_EQ(laps.size(), 1u); break;
    case Kind::Acceleration:
      ASSERT_EQ(laps.size(), 1u);
      // From a standing start ≤ 5 m before the line at a = µg ≈ 11.8 m/s², 75 m take at least 2.6 s.
      EXPECT_GT(laps[0]["time_s"].get<double>(), 2.6);
      EXPECT_LT(laps[0]["time_s"].get<double>(), 6.0);
      break;
    case Kind::Skidpad:
      ASSERT_EQ(laps.size(), 4u);
      // Each circle held as tightly as the issue asks of a trackdrive's lap 2.
      for (const auto& l : laps) {
        EXPECT_LE(l["cte_rms_m"].get<double>(), kLap2CteRms);
        EXPECT_LE(l["cte_max_m"].get<double>(), kLap2CteMax);
      }
      break;
    default: break;
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
  std::printf("%s: lap 2 %.3f s, friction-limited %.3f s (%+.1f %%)\n", c.name, l2["time_s"].get<double>(),
              reference, 100.0 * (l2["time_s"].get<double>() / reference - 1.0));
  EXPECT_LE(l2["time_s"].get<double>(), (1.0 + kLap2Margin) * reference);
  // Much faster than the friction limit would mean the reference or the timing is wrong.
  EXPECT_GE(l2["time_s"].get<double>(), 0.85 * reference);

  // The minimum-curvature option: the same two laps clean, lap 2 at least 1 % faster than on the centre line.
  const Drive race = drive(c.name, "trackdrive", 2, racing_config());
  expect_clean_finish(race);
  ASSERT_EQ(race.report["laps"].size(), 2u);
  const double race2 = race.report["laps"][1]["time_s"].get<double>();
  std::printf("%s: lap 2 on the min-curvature line %.3f s (%+.1f %% on the centre line's)\n", c.name, race2,
              100.0 * (race2 / l2["time_s"].get<double>() - 1.0));
  EXPECT_LE(race2, 0.99 * l2["time_s"].get<double>());
}

std::string case_name(const ::testing::TestParamInfo<TrackCase>& info) { return info.param.name; }

INSTANTIATE_TEST_SUITE_P(SharedTracks, AllTracks, ::testing::ValuesIn(cases()), case_name);

TEST(AllTracksTight, TenLapsAsAtFormulaStudentGermany) {
  // FSG's trackdrive is 10 laps (the paper's FSAC had 2). Laps 3–10 run on the same recorded line as lap 2: each
  // as clean as lap 2 (the issue's CTE figures) and within 1 % of its time, then the stop after the tenth.
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
