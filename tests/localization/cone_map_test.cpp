#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "localization/cone_map.hpp"

namespace fsd {
namespace {

ConeDetections detect(const std::vector<std::pair<Vec2, ConeColour>>& world, const Pose2& pose, double sigma,
                      std::mt19937& rng) {
  std::normal_distribution<double> n(0.0, sigma);
  ConeDetections d;
  for (const auto& [p, colour] : world) {
    Cone c;
    const Vec2 local = pose.inverse_transform(p) + Vec2(n(rng), n(rng));
    c.position = Vec3(local.x(), local.y(), 0);
    c.colour = colour;
    c.covariance = Eigen::Matrix2d::Identity() * sigma * sigma;
    d.cones.push_back(c);
  }
  return d;
}

using World = std::vector<std::pair<Vec2, ConeColour>>;

// One detection at p (vehicle frame).
Cone detection(const Vec2& p, ConeColour colour = ConeColour::Unknown, DetectionStage stage = DetectionStage::Truth,
               double confidence = 1.0) {
  Cone c;
  c.position = Vec3(p.x(), p.y(), 0);
  c.colour = colour;
  c.stage = stage;
  c.confidence = confidence;
  return c;
}

ConeDetections frame_of(std::vector<Cone> cones) {
  ConeDetections d;
  d.cones = std::move(cones);
  return d;
}

// Whether a mapped cone stands within 0.3 m of p.
bool mapped(const std::vector<Cone>& map, const Vec2& p) {
  return std::any_of(map.begin(), map.end(), [&](const Cone& c) { return (c.position.head<2>() - p).norm() < 0.3; });
}

// The map after driving along +x past `world`, `frames` detections (σ 5 cm) `step` m apart.
std::vector<Cone> drive_past(const World& world, int frames, double step, unsigned seed) {
  ConeMap map;
  std::mt19937 rng(seed);
  for (int k = 0; k < frames; ++k) {
    const Pose2 pose{step * k, 0.0, 0.0};
    map.update(detect(world, pose, 0.05, rng), pose);
  }
  return map.cones();
}

// One mapped cone per true cone, each within 5 cm of it and of its colour.
void expect_each_cone_mapped(const World& world, const std::vector<Cone>& cones) {
  ASSERT_EQ(cones.size(), world.size());
  for (const auto& [p, colour] : world) {
    const auto it = std::min_element(cones.begin(), cones.end(), [&](const Cone& a, const Cone& b) {
      return (a.position.head<2>() - p).norm() < (b.position.head<2>() - p).norm();
    });
    EXPECT_LT((it->position.head<2>() - p).norm(), 0.05);
    EXPECT_EQ(it->colour, colour);
  }
}

TEST(ConeMap, FusesRepeatedNoisyDetectionsToTheTruePosition) {
  const std::vector<std::pair<Vec2, ConeColour>> world{
      {{5, 2}, ConeColour::Blue}, {{5, -2}, ConeColour::Yellow}, {{9, 2}, ConeColour::Blue}};
  ConeMap map;
  std::mt19937 rng(3);
  for (int k = 0; k < 100; ++k) {
    const Pose2 pose{0.02 * k, 0.0, 0.01 * std::sin(k)};  // the car creeps forward
    map.update(detect(world, pose, 0.1, rng), pose);
  }
  const auto cones = map.cones();
  ASSERT_EQ(cones.size(), 3u);
  for (const auto& [p, colour] : world) {
    const auto it = std::min_element(cones.begin(), cones.end(), [&](const Cone& a, const Cone& b) {
      return (a.position.head<2>() - p).norm() < (b.position.head<2>() - p).norm();
    });
    // 100 samples of σ = 0.1 m: the mean is within ~3σ/√100 = 0.03 m.
    EXPECT_LT((it->position.head<2>() - p).norm(), 0.04);
    EXPECT_EQ(it->colour, colour);
  }
}

TEST(ConeMap, ColourByMajorityAndGhostsNeedConfirmation) {
  ConeMapConfig cfg;
  cfg.min_observations = 3;
  ConeMap map(cfg);
  // The cone at (4, 1), seen from frames 1 m apart (colours count once per place: AStandingCarsRepeatedColour...).
  auto one = [](Vec2 p, ConeColour c, double x) { return frame_of({detection(p - Vec2(x, 0), c)}); };
  map.update(one({4, 1}, ConeColour::Blue, 0), Pose2{0, 0, 0});
  map.update(one({4, 1}, ConeColour::Yellow, 1), Pose2{1, 0, 0});
  EXPECT_TRUE(map.cones().empty());  // two observations, not yet confirmed
  map.update(one({4, 1}, ConeColour::Blue, 2), Pose2{2, 0, 0});
  map.update(one({30, 0}, ConeColour::Blue, 3), Pose2{3, 0, 0});  // beyond max_range: ignored
  const auto cones = map.cones();
  ASSERT_EQ(cones.size(), 1u);
  EXPECT_EQ(cones[0].colour, ConeColour::Blue);
  EXPECT_NEAR(cones[0].confidence, 2.0 / 3.0, 1e-12);
}

TEST(ConeMap, ADoubledStartLineKeepsItsOrangeConesApartFromTheBoundaryCone) {
  // epfl_autoX_Vaudoise_Sponso: big orange cones 0.5 m before and after a boundary cone on each side of the start
  // line. Same-colour gating (1 m) alone merged the three into one and voted it the boundary's colour.
  const std::vector<std::pair<Vec2, ConeColour>> world{
      {{7.0, 1.5}, ConeColour::BigOrange},  {{7.5, 1.5}, ConeColour::Blue},    {{8.0, 1.5}, ConeColour::BigOrange},
      {{7.0, -1.5}, ConeColour::BigOrange}, {{7.5, -1.5}, ConeColour::Yellow}, {{8.0, -1.5}, ConeColour::BigOrange}};
  expect_each_cone_mapped(world, drive_past(world, 50, 0.05, 5));
}

TEST(ConeMap, SameColourConesNearerThanTheGateStayTwoCones) {
  // epfl_21_05_2023 and the skid pads: timing cones in pairs 0.5 m apart, both big orange (and blue/yellow
  // pairs at the skid pad's line). Seen in the same frames they are two cones; nearest-neighbour association
  // without one-to-one pairing fused each pair into one cone between them.
  const std::vector<std::pair<Vec2, ConeColour>> world{{{10.0, 1.5}, ConeColour::BigOrange},
                                                       {{10.5, 1.5}, ConeColour::BigOrange},
                                                       {{10.0, -1.5}, ConeColour::Yellow},
                                                       {{10.5, -1.5}, ConeColour::Yellow}};
  expect_each_cone_mapped(world, drive_past(world, 60, 0.1, 11));
}

TEST(ConeMap, AnOccasionallyWrongColourDoesNotSplitACone) {
  // One blue cone seen 200 times with σ = 0.1 m, one detection in ten called yellow: still one cone, blue.
  ConeMap map;
  std::mt19937 rng(9);
  std::bernoulli_distribution wrong(0.1);
  for (int k = 0; k < 200; ++k) {
    const Pose2 pose{0.01 * k, 0.0, 0.0};
    auto d = detect({{{6.0, 1.5}, ConeColour::Blue}}, pose, 0.1, rng);
    if (wrong(rng)) d.cones[0].colour = ConeColour::Yellow;
    map.update(d, pose);
  }
  const auto cones = map.cones();
  ASSERT_EQ(cones.size(), 1u);
  EXPECT_EQ(cones[0].colour, ConeColour::Blue);
}

TEST(ConeMap, AStandingCarsRepeatedColourCountsOnce) {
  // A yellow cone beside a timing line's big orange cones, 15 m ahead of a car standing at the start: the camera
  // names it big orange in each of sixty frames of the same view (the big cones' pixels in its image box), then
  // yellow in the frames it judges, 1 m apart, as the car drives off. The one view is one vote: yellow.
  ConeMap map;
  const Vec2 cone(15, 2);
  for (int k = 0; k < 60; ++k) map.update(frame_of({detection(cone, ConeColour::BigOrange)}), Pose2{});
  for (int k = 1; k <= 8; ++k) {
    const Pose2 pose{1.0 * k, 0, 0};
    map.update(frame_of({detection(pose.inverse_transform(cone), ConeColour::Yellow)}), pose);
  }
  const auto cones = map.cones();
  ASSERT_EQ(cones.size(), 1u);
  EXPECT_EQ(cones[0].colour, ConeColour::Yellow);
  EXPECT_NEAR(cones[0].confidence, 8.0 / 9.0, 1e-12);
}

TEST(ConeMap, AConeNamedOnlyWhileTheCarStandsHasThatColour) {
  // The orange cones at the end of an acceleration run's braking zone: the car stops before them and they are named
  // only in some of the frames it stands there. That place's one vote names them.
  ConeMap map;
  const Pose2 stopped{100, 0, 0};
  const Vec2 cone(113, 1.75);
  for (int k = 0; k < 60; ++k)
    map.update(
        frame_of({detection(stopped.inverse_transform(cone), k < 30 ? ConeColour::Unknown : ConeColour::Orange)}),
        stopped);
  const auto cones = map.cones();
  ASSERT_EQ(cones.size(), 1u);
  EXPECT_EQ(cones[0].colour, ConeColour::Orange);
}

// A tyre beside the track that the LiDAR takes for a cone, seen from afar (LiDAR only), then in the camera's view
// (rejected) and beside the car (LiDAR only again); a real cone next to it that the camera verifies once and doubts
// once; a cone the camera never sees. The car drives 1 m between frames: each verdict is from a new place.
TEST(ConeMap, WhatTheCameraRejectedMoreOftenThanItVerifiedIsWithheld) {
  ConeMapConfig cfg;
  cfg.min_rejections = 2;  // the rule on two verdicts (the default asks for 5: below)
  ConeMap map(cfg);
  int frame = 0;
  const Vec2 tyre(16, 3), cone(20, -2), unseen(12, 5);
  // One frame from 1 m further on: `lidar` detected by the LiDAR alone, `verified` by the camera, `rejected` by it.
  auto update = [&](std::vector<Vec2> lidar, std::vector<Vec2> verified, std::vector<Vec2> rejected) {
    const Pose2 pose{1.0 * frame++, 0, 0};
    ConeDetections d;
    for (const Vec2& p : lidar)
      d.cones.push_back(detection(pose.inverse_transform(p), ConeColour::Blue, DetectionStage::Lidar));
    for (const Vec2& p : verified)
      d.cones.push_back(detection(pose.inverse_transform(p), ConeColour::Blue, DetectionStage::Camera));
    std::vector<Cone> r;
    for (const Vec2& p : rejected)
      r.push_back(detection(pose.inverse_transform(p), ConeColour::Blue, DetectionStage::Lidar));
    map.update(d, pose, r);
  };
  for (int k = 0; k < 3; ++k) update({tyre, cone, unseen}, {}, {});  // far: LiDAR only, all three
  EXPECT_EQ(map.cones().size(), 3u);
  update({}, {cone}, {tyre + Vec2(0.1, 0)});     // in view: the tyre rejected twice,
  update({}, {}, {tyre + Vec2(0, -0.1), cone});  // the cone verified once and rejected once
  update({tyre, cone}, {}, {});                  // beside: LiDAR only again

  const auto cones = map.cones();
  EXPECT_FALSE(mapped(cones, tyre));   // rejected 2, verified 0
  EXPECT_TRUE(mapped(cones, cone));    // rejected 1 (< min_rejections), verified 1
  EXPECT_TRUE(mapped(cones, unseen));  // the camera never judged it
  EXPECT_EQ(cones.size(), 2u);
}

TEST(ConeMap, AStandingCarsRepeatedVerdictsCountOnce) {
  // A cone 12 m ahead, first detected by the LiDAR alone (no camera frame yet), that the camera then rejects in
  // every frame of a 6 s standing start (the same view sixty times: it stands behind another in the image) and
  // verifies in the eight frames it judges while the car drives off. The standing car's verdicts count once; it is
  // mapped. A tyre the camera rejects from nine places is not.
  ConeMap map;
  const Vec2 cone(12, 2), tyre(14, -4);
  enum class Verdict { None, Verified, Rejected };
  auto update = [&](const Pose2& pose, Verdict verdict) {
    const Vec2 c = pose.inverse_transform(cone), t = pose.inverse_transform(tyre);
    ConeDetections d = frame_of({detection(t, ConeColour::Unknown, DetectionStage::Lidar)});
    std::vector<Cone> rejected;
    if (verdict != Verdict::None) rejected.push_back(d.cones[0]);
    if (verdict == Verdict::Rejected)
      rejected.push_back(detection(c, ConeColour::Unknown, DetectionStage::Lidar));
    else
      d.cones.push_back(detection(c, ConeColour::Blue,
                                  verdict == Verdict::Verified ? DetectionStage::Camera : DetectionStage::Lidar));
    map.update(d, pose, rejected);
  };
  update(Pose2{}, Verdict::None);
  for (int k = 0; k < 60; ++k) update(Pose2{}, Verdict::Rejected);
  for (int k = 1; k <= 8; ++k) update(Pose2{0.8 * k, 0, 0}, Verdict::Verified);
  const auto cones = map.cones();
  EXPECT_TRUE(mapped(cones, cone));
  EXPECT_FALSE(mapped(cones, tyre));  // rejected from nine places, never verified
}

TEST(ConeMap, TwoCameraRejectionsDoNotWithholdAConeTheLidarSawNearOften) {
  // A blue cone the LiDAR sees in every frame while the car drives past, which the camera judges twice (a cone
  // half behind another in the image, at the image's edge) and rejects both times: by default (min_rejections 5)
  // it stays; a tyre rejected in five frames does not.
  ConeMap map;
  const Vec2 cone(12, 2), tyre(14, 4);
  for (int k = 0; k < 12; ++k) {
    const Pose2 pose{0.5 * k, 0, 0};
    const ConeDetections d =
        frame_of({detection(pose.inverse_transform(cone), ConeColour::Unknown, DetectionStage::Lidar),
                  detection(pose.inverse_transform(tyre), ConeColour::Unknown, DetectionStage::Lidar)});
    std::vector<Cone> rejected = {d.cones[1]};  // the tyre: rejected whenever seen (from k = 4: in view)
    if (k < 4) rejected.clear();
    if (k == 6 || k == 7) rejected.push_back(d.cones[0]);
    map.update(d, pose, rejected);
  }
  const auto cones = map.cones();
  EXPECT_TRUE(mapped(cones, cone));
  EXPECT_FALSE(mapped(cones, tyre));  // rejected 8 times, never verified
}

TEST(ConeMap, WhatWasSeenOnlyAFewTimesFromFarWaitsForMoreSightings) {
  // Detections carry the perception's confidence, which falls with range (perception.lidar.quality): 0.4 at 19 m.
  // A cone is reported once the confidences of its detections sum to min_support (2): five far sightings, two near.
  ConeMap map;
  auto frame = [](const Vec2& p, double confidence) {
    return frame_of({detection(p, ConeColour::Unknown, DetectionStage::Truth, confidence)});
  };
  const Vec2 far(19, 3), near(6, -2);
  for (int k = 0; k < 4; ++k) map.update(frame(far, 0.4), Pose2{});
  EXPECT_TRUE(map.cones().empty());  // 1.6: a lying tyre seen three or four times across the infield waits
  map.update(frame(far, 0.4), Pose2{});
  EXPECT_EQ(map.cones().size(), 1u);  // 2.0
  for (int k = 0; k < 2; ++k) map.update(frame(near, 1.0), Pose2{});
  EXPECT_EQ(map.cones().size(), 2u);
  // Verified by the camera, a far detection counts whole: two verified sightings at 19 m are a cone.
  const Vec2 verified_far(18, -5);
  for (int k = 0; k < 2; ++k) {
    map.update(frame_of({detection(verified_far, ConeColour::Unknown, DetectionStage::Camera, 0.4)}), Pose2{});
  }
  EXPECT_EQ(map.cones().size(), 3u);
}

// Ghost pruning: a tyre stack beside the track passes the LiDAR's size filter from far away (a few points) and not
// from near. Driving along +x past boundary cones every 5 m on y = ±2 and the stack at (10, 5): the stack is
// reported while the car is far from it, and withheld once the car came near and did not see it there.
struct PastAStack {
  World cones;
  Vec2 stack{10.0, 5.0};
  PastAStack() {
    for (double x = -20; x <= 40; x += 5) {
      cones.push_back({Vec2(x, 2.0), ConeColour::Blue});
      cones.push_back({Vec2(x, -2.0), ConeColour::Yellow});
    }
  }
  // One frame at x: every cone within 20 m; the stack only beyond 12 m.
  ConeDetections frame(double x, std::mt19937& rng) const {
    const Pose2 pose{x, 0.0, 0.0};
    World seen;
    for (const auto& c : cones)
      if ((c.first - pose.position()).norm() <= 20.0) seen.push_back(c);
    if ((stack - pose.position()).norm() > 12.0) seen.push_back({stack, ConeColour::Unknown});
    return detect(seen, pose, 0.03, rng);
  }
};

TEST(ConeMap, WhatTheCarCameNearAndDidNotSeeIsWithheld) {
  const PastAStack world;
  ConeMap map;
  std::mt19937 rng(7);
  double x = -20;
  for (; x < -2; x += 0.8) map.update(world.frame(x, rng), Pose2{x, 0, 0});
  EXPECT_TRUE(mapped(map.cones(), world.stack));  // seen from 12+ m, not yet come near
  for (; x < 40; x += 0.8) map.update(world.frame(x, rng), Pose2{x, 0, 0});
  const auto cones = map.cones();
  EXPECT_FALSE(mapped(cones, world.stack));
  for (const auto& [p, colour] : world.cones) EXPECT_TRUE(mapped(cones, p)) << p.transpose();
  EXPECT_EQ(cones.size(), world.cones.size());
}

TEST(ConeMap, GhostPruningOffKeepsWhatWasSeen) {
  const PastAStack world;
  ConeMapConfig cfg;
  cfg.min_misses = 0;
  ConeMap map(cfg);
  std::mt19937 rng(7);
  for (double x = -20; x < 40; x += 0.8) map.update(world.frame(x, rng), Pose2{x, 0, 0});
  EXPECT_TRUE(mapped(map.cones(), world.stack));
}

TEST(ConeMap, ACarStandingWithAConeHiddenDoesNotCountItOut) {
  // At the start the car stands for seconds: a cone 6 m ahead, seen twice, then hidden (behind a marshal, another
  // cone) for 60 frames, is still a cone; the misses of one place count once.
  ConeMap map;
  std::mt19937 rng(3);
  const World cone = {{Vec2(6.0, 1.5), ConeColour::Blue}};
  const Pose2 standing{};
  for (int k = 0; k < 2; ++k) map.update(detect(cone, standing, 0.03, rng), standing);
  for (int k = 0; k < 60; ++k) map.update(ConeDetections{}, standing);
  EXPECT_EQ(map.cones().size(), 1u);
}

// A post beside the track that the LiDAR misses from near and takes for a cone from far behind: the car drives past
// it at 5 m unseen, then detects it from 12+ m behind. It is a ghost like one first seen from far ahead (above): the
// frames of the last metres driven that had it in range count as misses. `pieces` detections 0.3 m apart stand for a
// tyre seen as two clusters: a piece born beside another is missed where that one was.
ConeMap drive_away_from_a_post(const ConeMapConfig& cfg, const PastAStack& world, int pieces) {
  ConeMap map(cfg);
  std::mt19937 rng(11);
  for (double x = -20; x < 40; x += 0.8) {
    ConeDetections d = world.frame(x, rng);
    std::erase_if(d.cones, [&](const Cone& c) {
      return (Pose2{x, 0, 0}.transform(c.position.head<2>()) - world.stack).norm() < 0.5;
    });
    if (x > world.stack.x() + 12.0)
      for (int k = 0; k < pieces; ++k) {
        Cone c = detection({world.stack.x() + 0.3 * k - x, world.stack.y()});
        c.covariance = Eigen::Matrix2d::Identity() * 0.03 * 0.03;
        d.cones.push_back(c);
      }
    map.update(d, Pose2{x, 0, 0});
  }
  return map;
}

TEST(ConeMap, WhatTheCarPassedUnseenAndDetectedFromBehindIsWithheld) {
  const PastAStack world;
  for (int pieces : {1, 2}) {
    const auto cones = drive_away_from_a_post({}, world, pieces).cones();
    EXPECT_EQ(cones.size(), world.cones.size()) << pieces << " pieces";
    for (const auto& [p, colour] : world.cones) EXPECT_TRUE(mapped(cones, p)) << p.transpose();
  }
  ConeMapConfig forgetful;  // without the memory of where the car was, the post is mapped
  forgetful.expect_memory = 0.0;
  EXPECT_EQ(drive_away_from_a_post(forgetful, world, 1).cones().size(), world.cones.size() + 1);
}

TEST(ConeMap, TwoConesSeenAsOneFromFarAreBothMappedWhenTheySplit) {
  // A timing line's doubled cones 0.5 m apart: one cluster between them up to 7 m, two from nearer. The second is
  // born where the car saw the first all along: no misses, reported at its second sighting.
  const Vec2 a(15.0, 2.5), b(15.0, 3.0);
  ConeMap map;
  std::mt19937 rng(5);
  for (double x = 0; x < 10; x += 0.4) {
    const Pose2 pose{x, 0, 0};
    const bool split = (a - pose.position()).norm() < 7.0;
    World seen = split ? World{{a, ConeColour::BigOrange}, {b, ConeColour::BigOrange}}
                       : World{{(a + b) / 2, ConeColour::BigOrange}};
    map.update(detect(seen, pose, 0.02, rng), pose);
  }
  const auto cones = map.cones();
  ASSERT_EQ(cones.size(), 2u);
  // Each near its own cone (the first still carries the far sightings between them: within 0.3 m).
  const auto nearest = [&](const Vec2& p) {
    return std::min_element(cones.begin(), cones.end(), [&](const Cone& x, const Cone& y) {
      return (x.position.head<2>() - p).norm() < (y.position.head<2>() - p).norm();
    });
  };
  EXPECT_NE(nearest(a), nearest(b));
  for (const Vec2& p : {a, b}) EXPECT_LT((nearest(p)->position.head<2>() - p).norm(), 0.3) << p.transpose();
}

// Loop closure: a layout mapped at the start by the true pose (t < 10 s), then seen again a lap later (t >= 60 s) by
// a pose that drifted by a known 1.4 m and 1.7 degrees: two copies. Corrected by the drift's inverse for the later
// sightings (identity for the earlier), every cone is one again, at its true place, with its colour.
TEST(ConeMap, CorrectMovesEachVisitWithItsPosesAndMergesTheCopies) {
  const World world{{{6, 1.5}, ConeColour::Blue},        {{6, -1.5}, ConeColour::Yellow},
                    {{9, 1.5}, ConeColour::Blue},        {{9, -1.5}, ConeColour::Yellow},
                    {{7.3, 2.2}, ConeColour::BigOrange}, {{7.3, -2.2}, ConeColour::BigOrange},
                    {{7.8, 2.2}, ConeColour::BigOrange}, {{7.8, -2.2}, ConeColour::BigOrange}};
  const Pose2 drift{-1.4, 0.0, 0.03};
  ConeMap map;
  std::mt19937 rng(5);
  for (int k = 0; k < 40; ++k) {
    const Pose2 truth{0.1 * k, 0.0, 0.0};
    ConeDetections d = detect(world, truth, 0.03, rng);
    d.stamp = 0.2 * k;
    map.update(d, truth);
  }
  for (int k = 0; k < 40; ++k) {
    const Pose2 truth{0.1 * k, 0.0, 0.0};
    ConeDetections d = detect(world, truth, 0.03, rng);
    d.stamp = 60 + 0.1 * k;
    map.update(d, drift * truth);  // what the drifted estimator believed
  }
  // The lap's seam: every cone twice. The first copies, which the drifted car came near and did not see where they
  // are mapped, are withheld meanwhile (ghost pruning); merged with their sightings of the second visit they count
  // as seen again.
  ASSERT_EQ(map.size(), 2 * world.size());
  EXPECT_LT(map.cones().size(), 2 * world.size());
  const int merged = map.correct([&](Stamp t) { return t < 30 ? Pose2{} : drift.inverse(); });
  EXPECT_EQ(merged, int(world.size()));
  expect_each_cone_mapped(world, map.cones());
  // Cones seen in the same frames stay two, however close the correction brings them: nothing more merges.
  EXPECT_EQ(map.correct([](Stamp) { return Pose2{}; }), 0);
  EXPECT_EQ(map.cones().size(), world.size());
}

TEST(ConeMap, CorrectKeepsConesSeenTogetherApart) {
  // Two same-colour cones 0.3 m apart (under the merge gate), seen in the same frames: two cones before and after.
  const World world{{{10.0, 1.5}, ConeColour::BigOrange}, {{10.3, 1.5}, ConeColour::BigOrange}};
  ConeMap map;
  std::mt19937 rng(9);
  for (int k = 0; k < 30; ++k) {
    const Pose2 pose{0.1 * k, 0.0, 0.0};
    ConeDetections d = detect(world, pose, 0.01, rng);
    d.stamp = 0.1 * k;
    map.update(d, pose);
  }
  ASSERT_EQ(map.cones().size(), 2u);
  EXPECT_EQ(map.correct([](Stamp) { return Pose2{0.5, 0.0, 0.0}; }), 0);
  ASSERT_EQ(map.cones().size(), 2u);
  for (const auto& c : map.cones()) EXPECT_NEAR(c.position.x(), c.position.x() < 10.65 ? 10.5 : 10.8, 0.05);
}

}  // namespace
}  // namespace fsd
