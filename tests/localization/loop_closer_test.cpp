// The LoopCloser against known truth: a car driven round a circle of cones (with a start line of big orange cones)
// by an estimator with a known drift (a scale error and a heading bias), its cones seen with seeded noise from the
// true poses. Fed as the Stack feeds it (after a closure the estimate is corrected from then on), the loop closes
// exactly once per lap, never before the lap's minimum distance nor away from the start, and the corrected pose is
// the true one. Where the start's scene is not seen again, or is ambiguous (a straight lane), nothing closes.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numbers>
#include <optional>
#include <random>

#include "localization/loop_closure/loop_closer.hpp"

namespace fsd::loop_closure {
namespace {

constexpr double kPi = std::numbers::pi;

struct World {
  std::vector<Vec2> cones;
  std::vector<ConeColour> colours;
  void add(const Vec2& p, ConeColour c) {
    cones.push_back(p);
    colours.push_back(c);
  }
  // What a car at `truth` sees: the cones ahead within 15 m, in its frame, with noise on each axis.
  std::vector<Cone> seen_from(const Pose2& truth, std::mt19937& rng, std::normal_distribution<double>& noise) const {
    std::vector<Cone> seen;
    for (std::size_t c = 0; c < cones.size(); ++c) {
      const Vec2 v = truth.inverse_transform(cones[c]);
      if (v.norm() > 15 || v.x() < 0) continue;
      Cone k;
      k.position = Vec3(v.x() + noise(rng), v.y() + noise(rng), 0);
      k.colour = colours[c];
      seen.push_back(k);
    }
    return seen;
  }
};

// A circle of radius 30 m driven counter-clockwise from (30, 0) heading +y (188 m a lap); cones every 3 m on rings
// 1.5 m inside (blue) and outside (yellow); big orange cones in pairs 4.7 and 7.3 m ahead of the start.
constexpr double kR = 30.0;
Pose2 on_circle(double s) {
  const double a = s / kR;
  return {kR * std::cos(a), kR * std::sin(a), wrap_angle(a + kPi / 2)};
}
World circle_world() {
  World w;
  for (double s = 0; s < 2 * kPi * kR - 1.5; s += 3.0) {
    const double a = s / kR;
    w.add({(kR - 1.5) * std::cos(a), (kR - 1.5) * std::sin(a)}, ConeColour::Blue);
    w.add({(kR + 1.5) * std::cos(a), (kR + 1.5) * std::sin(a)}, ConeColour::Yellow);
  }
  for (double s : {4.7, 7.3})
    for (double side : {-2.2, 2.2}) w.add(on_circle(s).transform(Vec2(0, side)), ConeColour::BigOrange);
  return w;
}

struct Drive {
  std::vector<LoopClosure> closures;
  std::vector<double> distance_at_closure;  // true distance driven
  std::vector<Pose2> truth_at_closure, corrected_at_closure;
  std::vector<double> error_before;  // m: the estimate's distance from the truth where the loop closed
  double worst_uncorrected = 0;      // the estimator's worst distance from the truth (its drift)
  double worst_corrected_after = 0;  // m from the truth of the corrected pose, over the frames after a closure
  std::vector<Cone> start_scene;     // the closer's, at the end
};

// Stands at the start for 20 frames, then drives `length` metres along `path` at 8 m/s, a perception frame every
// 0.5 m (cones within 15 m ahead, σ = 3 cm). The estimate integrates the true relative motion scaled by `scale` with
// `yaw_bias` rad per metre, and slides by `slide` (map frame) per metre driven (on a circle a scale or heading error
// alone comes back near zero after a whole lap); the closer's corrections are applied to it from then on, as the
// Stack does. With `delay` ≥ 0 the loop's solve is taken `delay` frames after the frame that closed it (feed, then
// finish before a later frame, as the Stack takes a worker's result at the start of a step): the frames in between
// are estimated uncorrected. Else add() solves it at once.
Drive drive(const World& w, const std::function<Pose2(double)>& path, double length, double scale, double yaw_bias,
            LoopCloserConfig cfg = {}, const Vec2& slide = {0.006, -0.006}, int delay = -1) {
  LoopCloser closer(cfg);
  std::mt19937 rng(11);
  std::normal_distribution<double> noise(0.0, 0.03);
  Drive out;
  Pose2 raw = path(0), map_from_raw;
  Pose2 prev_truth = path(0);
  struct Out {
    LoopSolveResult result;
    int frames = 0;  // fed since
    double s;
    Pose2 truth, estimate;
  };
  std::optional<Out> out_solve;
  auto take = [&](const LoopClosure& c, double s, const Pose2& truth, const Pose2& estimate) {
    map_from_raw = c.correction * map_from_raw;
    out.closures.push_back(c);
    out.distance_at_closure.push_back(std::max(0.0, s));
    out.truth_at_closure.push_back(truth);
    out.corrected_at_closure.push_back(c.correction * estimate);
    out.error_before.push_back((estimate.position() - truth.position()).norm());
  };
  const double step = 0.5;
  int frame = 0;
  for (double s = -20 * step; s <= length; s += step, ++frame) {
    if (out_solve && out_solve->frames++ == delay) {
      if (auto c = closer.finish(out_solve->result)) take(*c, out_solve->s, out_solve->truth, out_solve->estimate);
      out_solve.reset();
    }
    const Pose2 truth = path(std::max(0.0, s));
    Pose2 d = prev_truth.inverse() * truth;
    d.x *= scale, d.y *= scale, d.yaw += yaw_bias * std::hypot(d.x, d.y);
    const double ds = std::hypot(d.x, d.y);
    raw = raw * d;
    raw.x += slide.x() * ds, raw.y += slide.y() * ds;
    prev_truth = truth;
    out.worst_uncorrected = std::max(out.worst_uncorrected, (raw.position() - truth.position()).norm());
    const Pose2 estimate = map_from_raw * raw;
    if (!out.closures.empty())
      out.worst_corrected_after = std::max(out.worst_corrected_after, (estimate.position() - truth.position()).norm());
    const std::vector<Cone> seen = w.seen_from(truth, rng, noise);
    const Stamp t = 0.1 * frame;
    if (delay < 0) {
      if (auto c = closer.add(t, estimate, seen)) take(*c, s, truth, estimate);
    } else if (auto solve = closer.feed(t, estimate, seen)) {
      out_solve = Out{solve_loop(*solve), 0, s, truth, estimate};  // solved now, taken `delay` frames later
    }
  }
  EXPECT_EQ(closer.laps_closed(), int(out.closures.size()));
  out.start_scene = closer.start_scene();
  return out;
}

constexpr double kLap = 2 * kPi * kR;

TEST(LoopCloser, ClosesEachLapOnceAtTheStartAndPutsThePoseBackOnTheTruth) {
  const World w = circle_world();
  // 1 % short, 0.0001 rad/m of heading bias (1.1 degrees a lap) and 0.85 % sideways: over a metre off at the lap's
  // end.
  const Drive d = drive(w, on_circle, 2 * kLap + 20, 0.99, 0.0001);
  ASSERT_EQ(d.closures.size(), 2u) << "closed at " << (d.closures.empty() ? -1 : d.distance_at_closure[0]);
  const LoopCloserConfig cfg;
  for (std::size_t i = 0; i < d.closures.size(); ++i) {
    const LoopClosure& c = d.closures[i];
    EXPECT_EQ(c.lap, int(i) + 1);
    // Never early: a lap's minimum distance driven, back near the start (the true distance into the lap is within
    // the start's neighbourhood, before or after it).
    const double into_lap = d.distance_at_closure[i] - double(i) * kLap;
    EXPECT_GT(d.distance_at_closure[i], cfg.min_lap_distance * double(i + 1));
    EXPECT_GT(into_lap, kLap - cfg.near_start - 2.0) << "lap " << c.lap;
    EXPECT_LT(into_lap, kLap + cfg.near_start) << "lap " << c.lap;
    EXPECT_GE(c.pairs, cfg.alignment.min_pairs);
    // The corrected pose is the true one.
    const Pose2& truth = d.truth_at_closure[i];
    const Pose2& fixed = d.corrected_at_closure[i];
    EXPECT_GT(d.error_before[i], 1.0) << "lap " << c.lap;  // worth closing
    EXPECT_LT((fixed.position() - truth.position()).norm(), 0.3) << "lap " << c.lap;
    EXPECT_NEAR(wrap_angle(fixed.yaw - truth.yaw), 0.0, 0.03) << "lap " << c.lap;  // measured 0.26 m, 0.025 rad
    ASSERT_FALSE(c.keyframes.empty());
    EXPECT_EQ(c.keyframes.back().t, c.t);
  }
  // From the first closure on, the corrected estimate stays within the drift of one lap (it restarts there).
  EXPECT_LT(d.worst_corrected_after, 0.8 * d.worst_uncorrected);
}

TEST(LoopCloser, ASolveTakenFramesLaterClosesAsOneTakenAtOnce) {
  // The same drive with the loop's solve taken at once (add) and 1, 4 and 12 frames (0.5–6 m) later (feed, then
  // finish), the frames in between estimated uncorrected: the closures, the next lap's keyframes (those held while
  // the solve was out among them, replayed moved by the correction) and the start's scene are the same within
  // rounding, and on the truth.
  const World w = circle_world();
  const Drive now = drive(w, on_circle, 2 * kLap + 20, 0.99, 0.0001);
  ASSERT_EQ(now.closures.size(), 2u);
  for (int delay : {1, 4, 12}) {
    const Drive later = drive(w, on_circle, 2 * kLap + 20, 0.99, 0.0001, {}, {0.006, -0.006}, delay);
    ASSERT_EQ(later.closures.size(), now.closures.size()) << "delay " << delay;
    for (std::size_t i = 0; i < now.closures.size(); ++i) {
      const LoopClosure &a = now.closures[i], &b = later.closures[i];
      EXPECT_EQ(b.lap, a.lap);
      EXPECT_EQ(b.t, a.t) << "delay " << delay << " lap " << a.lap;
      EXPECT_NEAR(b.correction.x, a.correction.x, 1e-6);
      EXPECT_NEAR(b.correction.y, a.correction.y, 1e-6);
      EXPECT_NEAR(b.correction.yaw, a.correction.yaw, 1e-8);
      ASSERT_EQ(b.keyframes.size(), a.keyframes.size()) << "delay " << delay << " lap " << a.lap;
      double worst = 0;
      for (std::size_t k = 0; k < a.keyframes.size(); ++k) {
        EXPECT_EQ(b.keyframes[k].t, a.keyframes[k].t);
        worst = std::max({worst, (b.keyframes[k].estimate.position() - a.keyframes[k].estimate.position()).norm(),
                          (b.keyframes[k].optimised.position() - a.keyframes[k].optimised.position()).norm()});
      }
      EXPECT_LT(worst, 1e-6) << "delay " << delay << " lap " << a.lap;
      const Pose2& truth = later.truth_at_closure[i];
      EXPECT_LT((later.corrected_at_closure[i].position() - truth.position()).norm(), 0.3);
      EXPECT_NEAR(wrap_angle(later.corrected_at_closure[i].yaw - truth.yaw), 0.0, 0.03);
    }
    // Lap 2's first keyframes came from the `delay` frames fed while lap 1's solve was out (0.495 m estimated
    // each: a keyframe every third).
    const Stamp closed_at = later.closures[0].t;
    int held = 0;
    for (const auto& k : later.closures[1].keyframes) held += k.t > closed_at && k.t < closed_at + 0.1 * delay + 0.05;
    EXPECT_GE(held, delay / 3) << "delay " << delay;
    ASSERT_EQ(later.start_scene.size(), now.start_scene.size());
    for (std::size_t c = 0; c < now.start_scene.size(); ++c)
      EXPECT_LT((later.start_scene[c].position - now.start_scene[c].position).norm(), 1e-6);
    EXPECT_NEAR(later.worst_corrected_after, now.worst_corrected_after, 1e-6);
  }
}

TEST(LoopCloser, AFailedSolveLeavesTheLapToCloseAtTheNextKeyframe) {
  // The first solve handed out fails (its result unsolved); the frames fed meanwhile stay in the lap, and the loop
  // closes at a later keyframe of the same approach, onto the truth.
  const World w = circle_world();
  LoopCloser closer;
  std::mt19937 rng(11);
  std::normal_distribution<double> noise(0.0, 0.03);
  Pose2 raw = on_circle(0), prev = on_circle(0);
  int solves = 0;
  std::optional<LoopClosure> closed;
  Pose2 truth_there, estimate_there;
  std::optional<LoopSolve> first;
  for (int frame = 0; frame * 0.5 <= kLap + 20 && !closed; ++frame) {
    const Pose2 truth = on_circle(frame * 0.5);
    Pose2 d = prev.inverse() * truth;
    d.x *= 0.99, d.y *= 0.99, d.yaw += 0.0001 * std::hypot(d.x, d.y);
    raw = raw * d;
    raw.x += 0.006 * std::hypot(d.x, d.y), raw.y -= 0.006 * std::hypot(d.x, d.y);
    prev = truth;
    if (first && frame % 3 == 0) {  // 1.5 m later: the failed result comes back
      EXPECT_FALSE(closer.finish(LoopSolveResult{}));
      EXPECT_FALSE(closer.solving());
      first.reset();
    }
    const std::vector<Cone> seen = w.seen_from(truth, rng, noise);
    if (auto s = closer.feed(0.1 * frame, raw, seen)) {
      ++solves;
      if (solves == 1) {
        first = *s;
      } else {
        closed = closer.finish(solve_loop(*s));
        truth_there = truth, estimate_there = raw;
      }
    }
  }
  ASSERT_TRUE(closed);
  EXPECT_EQ(solves, 2);
  EXPECT_EQ(closed->lap, 1);
  EXPECT_EQ(closer.laps_closed(), 1);
  EXPECT_LT(((closed->correction * estimate_there).position() - truth_there.position()).norm(), 0.3);
}

TEST(LoopCloser, CorrectionAtIsIdentityBeforeTheLapAndTheNewestAfterIt) {
  LoopClosure c;
  c.keyframes = {{1.0, {0, 0, 0}, {0, 0, 0}}, {2.0, {10, 0, 0}, {10, 1, 0}}, {3.0, {20, 0, 0}, {20, 2, 0.1}}};
  EXPECT_NEAR(c.correction_at(0.5).y, 0.0, 1e-12);
  EXPECT_NEAR(c.correction_at(1.5).y, 0.5, 1e-12);  // half way between the first two keyframes' corrections
  const Pose2 last = c.keyframes.back().optimised * c.keyframes.back().estimate.inverse();
  EXPECT_NEAR(c.correction_at(9.0).x, last.x, 1e-12);
  EXPECT_NEAR(c.correction_at(9.0).yaw, 0.1, 1e-12);
}

TEST(LoopCloser, NoLoopWhereTheStartIsNotSeenAgainOrIsAmbiguous) {
  // A straight lane of blue and yellow cones every 3 m without big orange ones: driven 60 m out, round a
  // semicircle and back past the start. The start's cones are seen again after more than the lap's minimum
  // distance, but a lane slid along itself by a spacing fits as well: ambiguous, no loop.
  World lane;
  for (double x = -40; x <= 100; x += 3.0) {
    lane.add({x, 1.5}, ConeColour::Blue);
    lane.add({x, -1.5}, ConeColour::Yellow);
    lane.add({x, 7.5}, ConeColour::Blue);  // the return lane, 6 m to the left
    lane.add({x, 4.5}, ConeColour::Yellow);
  }
  const double out = 60, r = 3.0;
  auto out_and_back = [&](double s) -> Pose2 {
    if (s <= out) return {s, 0, 0};
    const double a = (s - out) / r;
    if (a <= kPi) return {out + r * std::sin(a), r - r * std::cos(a), wrap_angle(a)};
    return {out - (s - out - kPi * r), 2 * r, kPi};
  };
  const Drive back = drive(lane, out_and_back, 2 * out + kPi * r + 30, 0.994, 0.0004);
  EXPECT_TRUE(back.closures.empty()) << "closed at " << back.distance_at_closure[0] << " m";

  // A circle driven once round without its start line's orange cones: the arc is the same everywhere.
  World plain = circle_world();
  plain.cones.resize(plain.cones.size() - 4);
  plain.colours.resize(plain.colours.size() - 4);
  const Drive pd = drive(plain, on_circle, kLap + 20, 0.994, 0.0004);
  EXPECT_TRUE(pd.closures.empty()) << "closed at " << pd.distance_at_closure[0] << " m";

  // Never before the lap's minimum distance: the same lap, back at the start, with a minimum beyond it.
  LoopCloserConfig never;
  never.min_lap_distance = 1.5 * kLap;
  EXPECT_TRUE(drive(circle_world(), on_circle, kLap + 20, 0.994, 0.0004, never).closures.empty());
}

}  // namespace
}  // namespace fsd::loop_closure
