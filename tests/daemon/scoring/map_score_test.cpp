// The scorecard's map section on hand-placed cones: one-to-one pairing, misses, ghosts, position RMSE, colours.
#include <gtest/gtest.h>

#include <cmath>

#include <nlohmann/json.hpp>

#include "daemon/scoring/map_score.hpp"
#include "tests/cone_at.hpp"

namespace fsd {
namespace {

TrackCone truth_cone(double x, double y, ConeColour c) {
  TrackCone t;
  t.position = Vec2(x, y);
  t.colour = c;
  return t;
}

const auto mapped_cone = test::cone_at;

TEST(MapScore, PairsMissesGhostsErrorAndColour) {
  const std::vector<TrackCone> truth = {truth_cone(0, 0, ConeColour::Blue), truth_cone(5, 0, ConeColour::Blue),
                                        truth_cone(0, 3, ConeColour::Yellow), truth_cone(5, 3, ConeColour::Yellow)};
  const std::vector<Cone> map = {
      mapped_cone(0.1, 0, ConeColour::Blue),    // 0.1 m off
      mapped_cone(5, 0.2, ConeColour::Yellow),  // 0.2 m off, wrong colour
      mapped_cone(0, 3, ConeColour::Yellow),    // exact
      mapped_cone(20, 20, ConeColour::Blue),    // nothing there: a ghost
  };                                            // (5, 3) is missed
  const MapScore s = score_map(truth, map);
  EXPECT_EQ(s.true_cones, 4);
  EXPECT_EQ(s.mapped, 4);
  EXPECT_EQ(s.matched, 3);
  EXPECT_EQ(s.missed, 1);
  EXPECT_EQ(s.ghosts, 1);
  EXPECT_NEAR(s.rmse_m, std::sqrt((0.01 + 0.04 + 0.0) / 3.0), 1e-9);
  EXPECT_NEAR(s.colour_accuracy, 2.0 / 3.0, 1e-9);
  const auto j = to_json(s);
  EXPECT_EQ(j["missed"], 1);
  EXPECT_EQ(j["ghosts"], 1);
}

TEST(MapScore, TwoMappedConesOnOneTrueConeMakeOneGhost) {
  // A cone mapped twice (a failed association) pairs once, the nearer copy; the other is a ghost, and the true
  // neighbour 1 m away, outside the gate, stays missed rather than taking the copy.
  const std::vector<TrackCone> truth = {truth_cone(0, 0, ConeColour::BigOrange),
                                        truth_cone(1, 0, ConeColour::BigOrange)};
  const std::vector<Cone> map = {mapped_cone(0.05, 0, ConeColour::BigOrange),
                                 mapped_cone(-0.3, 0, ConeColour::BigOrange)};
  const MapScore s = score_map(truth, map);
  EXPECT_EQ(s.matched, 1);
  EXPECT_EQ(s.ghosts, 1);
  EXPECT_EQ(s.missed, 1);
  EXPECT_NEAR(s.rmse_m, 0.05, 1e-9);
  EXPECT_EQ(s.colour_accuracy, 1.0);
}

TEST(MapScore, AnEmptyMapMissesEverything) {
  const MapScore s = score_map({truth_cone(0, 0, ConeColour::Blue)}, {});
  EXPECT_EQ(s.missed, 1);
  EXPECT_EQ(s.ghosts, 0);
  EXPECT_EQ(s.matched, 0);
  EXPECT_EQ(s.rmse_m, 0.0);
  EXPECT_EQ(s.colour_accuracy, 0.0);
}

}  // namespace
}  // namespace fsd
