// A live parameter change lands in the typed struct through the section's member pointer, for each value type.
#include <gtest/gtest.h>

#include "common/config.hpp"

namespace fsd {
namespace {

struct Knobs {
  double speed = 5.0;
  int laps = 2;
  bool verbose = false;
  std::string mode = "fast";
};

const ConfigSection<Knobs>& knobs() {
  static const auto s = ConfigSection<Knobs>("k")
                            .number("speed", &Knobs::speed, 0.0, 30.0, "m/s", "speed", true)
                            .integer("laps", &Knobs::laps, 1, 10, "", "laps", true)
                            .boolean("verbose", &Knobs::verbose, "talk more", true)
                            .string("mode", &Knobs::mode, {"fast", "safe"}, "mode");
  return s;
}

TEST(ConfigSectionApply, SetsAndReadsEachMemberByItsKey) {
  Knobs k;
  EXPECT_TRUE(knobs().apply("k.speed", 7.5, k));
  EXPECT_TRUE(knobs().apply("k.laps", 4.0, k));
  EXPECT_TRUE(knobs().apply("k.verbose", 1.0, k));
  EXPECT_EQ(k.speed, 7.5);
  EXPECT_EQ(k.laps, 4);
  EXPECT_TRUE(k.verbose);
  EXPECT_EQ(knobs().value("k.speed", k), 7.5);
  EXPECT_EQ(knobs().value("k.laps", k), 4.0);
  EXPECT_EQ(knobs().value("k.verbose", k), 1.0);
  EXPECT_TRUE(knobs().apply("k.verbose", 0.0, k));
  EXPECT_FALSE(k.verbose);
}

TEST(ConfigSectionApply, OtherKeysAndStringsAreNotApplied) {
  Knobs k;
  EXPECT_FALSE(knobs().apply("k.mode", 1.0, k));  // strings are never live parameters
  EXPECT_FALSE(knobs().apply("speed", 1.0, k));   // the full dotted key only
  EXPECT_FALSE(knobs().apply("other.speed", 1.0, k));
  EXPECT_EQ(k.speed, 5.0);
  EXPECT_FALSE(knobs().value("k.mode", k));
}

}  // namespace
}  // namespace fsd
