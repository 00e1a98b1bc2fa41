// The camera's colour stage on cone crops drawn by hand (tests/perception/camera_drawn_cone.hpp): every cone colour
// at 20 to 400 px, under dim and bright light, with colour casts, on asphalt, grass, sky, concrete and gravel. The
// truth is the paint the test chose. Grey, mixed and green inputs must come out unknown rather than a wrong colour.
#include <gtest/gtest.h>

#include <cstdio>
#include <map>
#include <string>

#include "perception/camera/cone_colour.hpp"
#include "tests/perception/camera_drawn_cone.hpp"

namespace fsd {
namespace {

using test::Background;
using test::DrawnCone;

struct Tally {
  int right = 0, unknown = 0, wrong = 0;
  int total() const { return right + unknown + wrong; }
};

// A crop as a person cuts one from a photo: the cone roughly centred and filling most of the height.
DrawnCone random_crop(ConeColour colour, int height, cv::RNG& rng, std::uint64_t seed, bool loose = false) {
  DrawnCone d;
  test::paint_cone(d, colour, rng);
  d.crop = cv::Size(std::max(8, static_cast<int>(height * rng.uniform(0.6, 1.0))), height);
  d.fill = loose ? rng.uniform(0.45, 0.65) : rng.uniform(0.65, 0.95);
  d.centre = loose ? rng.uniform(0.35, 0.65) : rng.uniform(0.42, 0.58);
  d.light = rng.uniform(0.5, 1.4);
  d.cast = cv::Scalar(rng.uniform(0.9, 1.1), rng.uniform(0.96, 1.04), rng.uniform(0.9, 1.1));
  d.background = static_cast<Background>(rng.uniform(0, 5));
  d.noise = rng.uniform(1.0, 6.0);
  d.blur = rng.uniform(0.3, 1.2) * std::max(1.0, height / 100.0);
  d.seed = seed;
  return d;
}

// Classifies crops of every colour at every size; the tallies per colour and in all.
Tally classify_crops(bool loose, std::uint64_t rng_seed) {
  const ConeColourClassifier classifier;
  std::map<ConeColour, Tally> tally;
  Tally all;
  cv::RNG rng(rng_seed);
  std::uint64_t seed = rng_seed;
  for (const ConeColour colour :
       {ConeColour::Blue, ConeColour::Yellow, ConeColour::Orange, ConeColour::BigOrange, ConeColour::Red})
    for (const int height : {20, 30, 45, 70, 110, 180, 280, 400})
      for (int k = 0; k < 12; ++k) {
        const DrawnCone d = random_crop(colour, height, rng, seed++, loose);
        const cv::Mat img = test::draw_cone(d);
        const ColourResult r = classifier.classify(img, ConeColourClassifier::crop_view(img.size()));
        Tally& t = tally[colour];
        // A crop has no scale: big orange is told from orange by its two stripes, which a cone under ~40 px does not
        // resolve (each is 12 % of its height). The stage on a camera frame measures the height instead.
        const double cone_px = d.fill * height;
        const bool size_unresolvable =
            colour == ConeColour::BigOrange && cone_px < 40 && r.colour == ConeColour::Orange;
        if (r.colour == colour || size_unresolvable)
          ++t.right, ++all.right;
        else if (r.colour == ConeColour::Unknown)
          ++t.unknown, ++all.unknown;
        else
          ++t.wrong, ++all.wrong;
        if (r.colour != colour && !size_unresolvable)
          std::printf(
              "  miss: %s at %d px (light %.2f, background %d) came out %s (best %s, confidence %.2f, hue %.0f, "
              "stripes %d)\n",
              std::string(to_string(colour)).c_str(), height, d.light, static_cast<int>(d.background),
              std::string(to_string(r.colour)).c_str(), std::string(to_string(r.best)).c_str(), r.confidence, r.hue,
              r.stripes);
      }
  for (const auto& [colour, t] : tally)
    std::printf("  %-10s right %3d unknown %2d wrong %2d of %d\n", std::string(to_string(colour)).c_str(), t.right,
                t.unknown, t.wrong, t.total());
  return all;
}

TEST(CameraColourDrawn, EveryColourAtEverySizeAndLight) {
  const Tally all = classify_crops(false, 20240617);
  EXPECT_GE(all.right, 0.98 * all.total()) << all.unknown << " unknown, " << all.wrong << " wrong";
  EXPECT_LE(all.wrong, 0.01 * all.total());
}

// Crops cut loosely: the cone at half the height, off centre, more background around it.
TEST(CameraColourDrawn, LooseCropsWithMoreBackground) {
  const Tally all = classify_crops(true, 777);
  EXPECT_GE(all.right, 0.95 * all.total()) << all.unknown << " unknown, " << all.wrong << " wrong";
  EXPECT_LE(all.wrong, 0.01 * all.total());
}

// Things that are not a cone colour, or between two: a grey cone, a dark tyre, grass-green and purple objects, and
// amber paint on the edge of orange and yellow (41°), which must not be forced into either.
TEST(CameraColourDrawn, GreyDarkGreenPurpleAndAmberAreUnknown) {
  const ConeColourClassifier classifier;
  cv::RNG rng(5);
  const struct {
    const char* what;
    cv::Scalar body, stripe;
    std::vector<std::array<double, 2>> stripes;
  } cases[] = {
      {"grey cone", {128, 128, 128}, {235, 235, 235}, {{0.38, 0.62}}},
      {"dark tyre-grey", {40, 42, 45}, {60, 60, 60}, {}},
      {"grass green", {40, 150, 60}, {40, 150, 60}, {}},
      {"purple", {150, 40, 140}, {235, 235, 235}, {{0.38, 0.62}}},
      {"amber", {10, 162, 235}, {235, 235, 235}, {{0.38, 0.62}}},
  };
  for (const auto& c : cases)
    for (const int height : {24, 60, 150, 360})
      for (const double light : {0.6, 0.8, 1.0}) {
        DrawnCone d;
        d.body = c.body;
        d.stripe = c.stripe;
        d.stripes = c.stripes;
        d.crop = cv::Size(height * 3 / 4, height);
        d.light = light;
        d.background = static_cast<Background>(rng.uniform(0, 5));
        d.seed = static_cast<std::uint64_t>(height);
        const cv::Mat img = test::draw_cone(d);
        const ColourResult r = classifier.classify(img, ConeColourClassifier::crop_view(img.size()));
        EXPECT_EQ(r.colour, ConeColour::Unknown)
            << c.what << " at " << height << " px, light " << light << ": " << to_string(r.colour) << " (confidence "
            << r.confidence << ", hue " << r.hue << ")";
      }
}

// An ROI as the stage cuts it at 100 px/m: 0.44 m wide, from 0.58 m above the base to 0.06 m below it. A small
// orange cone (0.325 m) is orange, a big one (0.505 m) big orange, measured from the paint's height; the LiDAR's
// height, when given, decides instead.
TEST(CameraColourScale, BigOrangeFromTheProjectedScaleOrTheLidarHeight) {
  const ConeColourClassifier classifier;
  const double px_per_m = 100;
  const cv::Size roi(44, 64);
  const ConeView view{cv::Point2d(22, 58), px_per_m};
  cv::RNG rng(9);
  for (const bool big : {false, true})
    for (const double light : {0.6, 1.0, 1.25}) {
      DrawnCone d;
      test::paint_cone(d, big ? ConeColour::BigOrange : ConeColour::Orange, rng);
      d.crop = roi;
      d.fill = (big ? 0.505 : 0.325) * px_per_m / roi.height;
      d.base = 58.0 / roi.height;
      d.light = light;
      d.noise = 2.0;
      const cv::Mat img = test::draw_cone(d);
      const ColourResult r = classifier.classify(img, view);
      EXPECT_EQ(r.colour, big ? ConeColour::BigOrange : ConeColour::Orange)
          << "light " << light << ", height " << r.height;
      EXPECT_NEAR(r.height, big ? 0.505 : 0.325, 0.06) << "light " << light;
      // The LiDAR's height overrides the image: the envelope is the better measure of size.
      EXPECT_EQ(classifier.classify(img, view, 0.50).colour, ConeColour::BigOrange);
      EXPECT_EQ(classifier.classify(img, view, 0.31).colour, ConeColour::Orange);
    }
}

// Far away the stage's ROI is a few pixels across and the paint's height is good to a pixel or so, the projected
// base less so (the car's pitch, the mount: the virtual car's small cones measured up to 0.47 m): cones 15 m away
// (40 px/m, an ROI of 18 x 26 px) with the base row up to 4 px off either way. A small orange cone is never taken for
// a big one (the bar is 0.415 m); a big one is big orange at least half the time, else orange.
TEST(CameraColourScale, AFarSmallOrangeConeIsNotTakenForABigOne) {
  const ConeColourClassifier classifier;
  const double px_per_m = 40;
  const cv::Size roi(18, 26);
  const double base_row = 0.58 * px_per_m;
  cv::RNG rng(21);
  int small_as_big = 0, big_as_big = 0, big_total = 0;
  for (const bool big : {false, true})
    for (const double offset : {-4.0, -3.0, -2.0, -1.0, 0.0, 1.0, 2.0, 3.0, 4.0})
      for (int k = 0; k < 6; ++k) {
        DrawnCone d;
        test::paint_cone(d, big ? ConeColour::BigOrange : ConeColour::Orange, rng);
        d.crop = roi;
        d.fill = (big ? 0.505 : 0.325) * px_per_m / roi.height;
        d.base = base_row / roi.height;
        d.centre = rng.uniform(0.45, 0.55);
        d.light = rng.uniform(0.7, 1.2);
        d.noise = 2.0;
        d.seed = static_cast<std::uint64_t>(100 + k);
        const ConeView view{cv::Point2d(roi.width / 2.0, base_row + offset), px_per_m};
        const ColourResult r = classifier.classify(test::draw_cone(d), view);
        if (r.colour == ConeColour::Unknown) continue;
        EXPECT_TRUE(r.colour == ConeColour::Orange || r.colour == ConeColour::BigOrange);
        if (big) {
          ++big_total;
          big_as_big += r.colour == ConeColour::BigOrange;
        } else {
          small_as_big += r.colour == ConeColour::BigOrange;
          EXPECT_NE(r.colour, ConeColour::BigOrange) << "offset " << offset << " px, measured " << r.height << " m";
        }
      }
  EXPECT_EQ(small_as_big, 0);
  EXPECT_GE(big_as_big, big_total / 2) << big_as_big << " of " << big_total;
}

// FSG events have no red cones: with red off, a red hue reads as orange rather than naming a colour not on track.
TEST(CameraColourDrawn, RedFoldsIntoOrangeWhenRedIsOff) {
  ConeColourConfig no_red;
  no_red.red = false;
  cv::RNG rng(11);
  DrawnCone d;
  test::paint_cone(d, ConeColour::Red, rng);
  const cv::Mat img = test::draw_cone(d);
  EXPECT_EQ(ConeColourClassifier().classify(img, ConeColourClassifier::crop_view(img.size())).colour, ConeColour::Red);
  EXPECT_EQ(ConeColourClassifier(no_red).classify(img, ConeColourClassifier::crop_view(img.size())).colour,
            ConeColour::Orange);
}

}  // namespace
}  // namespace fsd
