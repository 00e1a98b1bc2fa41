// Control on layouts it has never seen (tests/daemon/layouts/generated_layouts.hpp): generated layouts driven end
// to end by the fsd binary on the truth sources and judged by the scorecard. Odd seeds are the rules' layouts, even
// seeds have the classes of public layouts mixed in (`--irregular`: hairpin chains, a whole lap round one 9 m turn,
// hand-placed cones, an inside cone out of its ring, a lane narrowed below 3 m, a braking zone closed 25 m after the
// finish; docs/track-generator.md).
//   GeneratedTracks.CiSubset     the CI subset: 40 layouts of every kind, two at a time; >= 99.5 % must be clean
//                                (finished, no cone hit, stopped in the zone); every other one is listed
// The whole sweep (600 layouts; docs/control.md "Generated layouts") is a figure runner, not a test:
//   build/bench/generated_layouts_sweep      (bench/generated_layouts_sweep.cpp; FSD_SWEEP_SEEDS, FSD_SWEEP_JOBS)
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "tests/daemon/layouts/generated_layouts.hpp"

namespace fsd {
namespace {

using test::generated::Case;
using test::generated::describe;
using test::generated::drive_all;
using test::generated::Outcome;

// The CI subset: ≥ 40 layouts mixing every kind.
std::vector<Case> ci_cases() {
  std::vector<Case> v;
  for (int s = 1; s <= 14; ++s) v.push_back({"trackdrive", s});
  for (int s = 1; s <= 12; ++s) v.push_back({"autocross", s});
  for (int s = 1; s <= 7; ++s) v.push_back({"acceleration", s});
  for (int s = 1; s <= 7; ++s) v.push_back({"skidpad", s});
  return v;
}

// The subset as one test, two layouts at a time: every failure is listed with its seed and how to reproduce it.
// Held to the target over the whole sweep, >= 99.5 % clean (of 40: every one; the runs are deterministic);
// docs/control.md "Generated layouts" has the whole sweep's figures.
TEST(GeneratedTracks, CiSubset) {
  const std::vector<Case> cases = ci_cases();
  const std::vector<Outcome> out = drive_all(cases, 2);
  int clean = 0;
  for (const auto& o : out) {
    EXPECT_TRUE(o.ran) << describe(o);
    clean += o.clean;
    if (!o.clean) std::printf("NOT CLEAN: %s\n  reproduce: %s\n", describe(o).c_str(), o.command.c_str());
    if (o.c.kind == "trackdrive" && o.clean) {
      ASSERT_EQ(o.laps.size(), 2u) << describe(o);
      ASSERT_GT(o.reference, 0.0) << describe(o);
      // Lap 2 on the recorded line: not faster than the friction limit allows (the reference would be wrong).
      EXPECT_GE(o.laps[1], 0.85 * o.reference) << describe(o);
    }
  }
  std::printf("clean %d of %zu\n", clean, out.size());
  EXPECT_GE(clean, static_cast<int>(std::ceil(0.995 * static_cast<double>(out.size()))))
      << "more than 0.5 % of the CI subset is not clean (listed above)";
}

}  // namespace
}  // namespace fsd
