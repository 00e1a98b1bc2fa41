// The colour from the LiDAR's reflectivity on hand-made clusters: points of known height and reflectivity on a flat
// ground (z = 0), as the lasers would return them from a blue cone, a yellow cone, and a black tyre of the same
// size.
#include <gtest/gtest.h>

#include <vector>

#include "perception/intensity_colour.hpp"

namespace fsd {
namespace {

// A small cone's cluster `range` ahead: `per_height` points at each height, with the reflectivity `paint(h)`.
template <class Paint>
ConeCandidate cluster(const std::vector<double>& heights, Paint paint, int per_height = 4, double range = 5.0) {
  ConeCandidate c;
  c.range = range;
  c.position = Vec3(range, 0, 0);
  for (double h : heights)
    for (int k = 0; k < per_height; ++k) {
      Point p;
      p.x = static_cast<float>(range);
      p.y = 0.02f * static_cast<float>(k);
      p.z = static_cast<float>(h);
      p.intensity = static_cast<float>(paint(h));
      c.cloud.push_back(p);
    }
  c.points = static_cast<std::uint32_t>(c.cloud.size());
  return c;
}

// FSG small cone (0.325 m): stripe from 38 to 62 % of the height.
bool in_stripe(double h) { return h >= 0.38 * 0.325 && h <= 0.62 * 0.325; }

TEST(IntensityColour, TheStripeAgainstTheBodyTellsBlueFromYellow) {
  const GroundSurface ground(GroundPlane{});
  const IntensityColourClassifier classify;
  const std::vector<double> rings{0.05, 0.16, 0.27};  // one laser through the stripe, two through the body
  EXPECT_EQ(classify.classify(cluster(rings, [](double h) { return in_stripe(h) ? 95.0 : 22.0; }), ground).colour,
            ConeColour::Blue);
  EXPECT_EQ(classify.classify(cluster(rings, [](double h) { return in_stripe(h) ? 8.0 : 70.0; }), ground).colour,
            ConeColour::Yellow);
}

TEST(IntensityColour, ABodyAloneIsBlueWhenDarkButNotWhenBlack) {
  // The lasers cross below and above the stripe only.
  const GroundSurface ground(GroundPlane{});
  const IntensityColourClassifier classify;
  const std::vector<double> rings{0.06, 0.25};
  EXPECT_EQ(classify.classify(cluster(rings, [](double) { return 22.0; }), ground).colour, ConeColour::Blue);
  EXPECT_EQ(classify.classify(cluster(rings, [](double) { return 70.0; }), ground).colour, ConeColour::Yellow);
  // Black rubber (a tyre the size filter let through): no colour rather than blue.
  EXPECT_EQ(classify.classify(cluster(rings, [](double) { return 6.0; }), ground).colour, ConeColour::Unknown);
}

TEST(IntensityColour, FarOneLaserBelowTheStripeNamesTheBody) {
  // 16 m away the −1° laser of a sensor 0.35 m up crosses a cone 0.07 m up: below the stripe (0.1235 m) by more than
  // the laser's footprint and the ground's uncertainty there (2 mm per m: 0.032 m), above the ground threshold.
  const GroundSurface ground(GroundPlane{});
  const IntensityColourClassifier classify;
  const std::vector<double> low{0.07};
  const auto body = [](double level) { return [level](double) { return level; }; };
  EXPECT_EQ(classify.classify(cluster(low, body(22.0), 6, 16.0), ground).colour, ConeColour::Blue);
  EXPECT_EQ(classify.classify(cluster(low, body(70.0), 6, 16.0), ground).colour, ConeColour::Yellow);
  EXPECT_EQ(classify.classify(cluster(low, body(6.0), 6, 16.0), ground).colour, ConeColour::Unknown);  // rubber
  // Nearer the stripe than that margin (0.10 m up at 16 m), a blue cone's white stripe could read as a bright body:
  // no colour.
  EXPECT_EQ(classify.classify(cluster({0.10}, body(95.0), 6, 16.0), ground).colour, ConeColour::Unknown);
  // Returns that are not one paint: the heights are off by centimetres (accumulated frames of a pitching car), the
  // stripe is among them: a blue cone's white stripe beside its body, or half of them as dark as blue plastic among
  // bright ones (yellow's black stripe). No colour.
  int k = 0;
  EXPECT_EQ(classify
                .classify(cluster(
                              low, [&](double) { return ++k % 2 ? 20.0 : 92.0; }, 8, 16.0),
                          ground)
                .colour,
            ConeColour::Unknown);
  EXPECT_EQ(classify
                .classify(cluster(
                              low, [&](double) { return ++k % 2 ? 8.0 : 68.0; }, 8, 16.0),
                          ground)
                .colour,
            ConeColour::Unknown);
  // A yellow body with one dim return at its grazing edge is yellow still.
  EXPECT_EQ(classify
                .classify(cluster(
                              low, [&](double) { return ++k % 8 ? 66.0 : 24.0; }, 8, 16.0),
                          ground)
                .colour,
            ConeColour::Yellow);
  // Too few returns, beyond far_range, or a big cone (its stripes are elsewhere): no colour.
  EXPECT_EQ(classify.classify(cluster(low, body(22.0), 3, 16.0), ground).colour, ConeColour::Unknown);
  EXPECT_EQ(classify.classify(cluster(low, body(22.0), 6, 21.0), ground).colour, ConeColour::Unknown);
  ConeCandidate b = cluster(low, body(22.0), 6, 16.0);
  b.big = true;
  EXPECT_EQ(classify.classify(b, ground).colour, ConeColour::Unknown);
}

// FSG big cone (0.505 m): white stripes from 28 to 40 % and from 58 to 70 % of its height.
bool in_big_stripe(double h) {
  const double f = h / 0.505;
  return (f >= 0.28 && f <= 0.40) || (f >= 0.58 && f <= 0.70);
}

ConeCandidate big(ConeCandidate c) {
  c.big = true;
  return c;
}

TEST(IntensityColour, ABigConeIsBigOrangeByItsStripesOrItsOrangeBody) {
  const GroundSurface ground(GroundPlane{});
  const IntensityColourClassifier classify;
  const auto orange = [](double h) { return in_big_stripe(h) ? 95.0 : 55.0; };
  // Three lasers, the middle one through the lower stripe.
  EXPECT_EQ(classify.classify(big(cluster({0.06, 0.17, 0.45}, orange)), ground).colour, ConeColour::BigOrange);
  // Two lasers ~7 m away, both between the stripes' bands (0.23 and 0.47 m): the orange body alone names it.
  const std::vector<double> between{0.23, 0.47};
  EXPECT_FALSE(in_big_stripe(0.23) || in_big_stripe(0.47));
  EXPECT_EQ(classify.classify(big(cluster(between, orange)), ground).colour, ConeColour::BigOrange);
  // Not orange plastic: black rubber (a tyre stack), dark blue, bright paint (a post): no colour.
  for (double body : {6.0, 22.0, 80.0})
    EXPECT_EQ(classify.classify(big(cluster(between, [&](double) { return body; })), ground).colour,
              ConeColour::Unknown)
        << body;
  // A laser through a stripe that is not brighter than the body: not a striped cone.
  EXPECT_EQ(classify.classify(big(cluster({0.06, 0.17, 0.45}, [](double) { return 55.0; })), ground).colour,
            ConeColour::Unknown);
}

TEST(IntensityColour, BlackRubberIsNoConeButAYellowConesBlackStripeIs) {
  // The virtual car's paints (drivers/sim: tyre 6, yellow body 70 and stripe 8, blue body 22): what a cone's body
  // returns is never as dark as rubber; a yellow cone's stripe is.
  const GroundSurface ground(GroundPlane{});
  const IntensityColourClassifier classify;
  const auto flat = [](double level) { return [level](double) { return level; }; };
  // A tyre stack's foot, one laser at 0.09 m (below the stripe band): black.
  EXPECT_TRUE(classify.black(cluster({0.09}, flat(6.0)), ground));
  // Far from the colour's range, it still is (the rejection does not depend on max_range or enabled).
  ConeCandidate far = cluster({0.05}, flat(5.0));
  far.range = 17.0;
  EXPECT_TRUE(classify.black(far, ground));
  // A yellow cone one laser crosses through its black stripe: not judged, so not black.
  EXPECT_FALSE(classify.black(cluster({0.16}, flat(8.0)), ground));
  // Cone bodies: yellow, dark blue, and a blue body darker than the colour names (10: Unknown, still no rubber).
  EXPECT_FALSE(classify.black(cluster({0.05, 0.25}, flat(70.0)), ground));
  EXPECT_FALSE(classify.black(cluster({0.05, 0.25}, flat(22.0)), ground));
  EXPECT_EQ(classify.classify(cluster({0.05, 0.25}, flat(10.0)), ground).colour, ConeColour::Unknown);
  EXPECT_FALSE(classify.black(cluster({0.05, 0.25}, flat(10.0)), ground));
  // Dark below, bright above: not rubber.
  EXPECT_FALSE(classify.black(cluster({0.05, 0.25}, [](double h) { return h < 0.1 ? 6.0 : 70.0; }), ground));
  // Too few returns in the body bands to judge.
  EXPECT_FALSE(classify.black(cluster({0.05}, flat(6.0), 3), ground));
}

}  // namespace
}  // namespace fsd
