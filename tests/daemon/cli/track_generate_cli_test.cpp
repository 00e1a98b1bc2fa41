// `fsd track generate` as a user runs it: stdout or --out, the same bytes for the same seed, the project's
// loader reads the file, the options for public layouts, bad options exit 2 naming what is wrong.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

#include "common/track.hpp"
#include "tests/daemon/fsd_process.hpp"
#include "tests/scratch_dir.hpp"

namespace fsd {
namespace {

std::string slurp(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::ostringstream s;
  s << f.rdbuf();
  return s.str();
}

TEST(TrackGenerateCli, StdoutAndOutFileAreTheSameLoadableBytes) {
  for (const std::string kind : {"trackdrive", "autocross", "acceleration", "skidpad"}) {
    SCOPED_TRACE(kind);
    std::string out1, out2, log;
    ASSERT_EQ(test::run_fsd("track generate --seed 7 --kind " + kind + " 2>/dev/null", &out1), 0);
    ASSERT_EQ(test::run_fsd("track generate --seed 7 --kind " + kind + " 2>/dev/null", &out2), 0);
    EXPECT_EQ(out1, out2);
    const std::string file = test::scratch_path("cli_" + kind + ".csv");
    ASSERT_EQ(test::run_fsd("track generate --seed 7 --kind " + kind + " --out " + file, &log), 0) << log;
    EXPECT_EQ(slurp(file), out1);
    const Track t = load_track(file);
    EXPECT_GT(t.count(ConeRole::Left), 10u);
    EXPECT_GT(t.count(ConeRole::Right), 10u);
    EXPECT_GE(t.count(ConeRole::Timing), 4u);
  }
}

TEST(TrackGenerateCli, OptionsChangeTheLayout) {
  std::string a, b;
  ASSERT_EQ(test::run_fsd("track generate --seed 3 --width 3 2>/dev/null", &a), 0);
  ASSERT_EQ(test::run_fsd("track generate --seed 3 --width 4.5 2>/dev/null", &b), 0);
  EXPECT_NE(a, b);
}

// The options for what public layouts have reach the generator: each changes the layout into a file the loader
// reads (the circle: about 16 cones, no timing cones); the mix gives the same bytes again.
TEST(TrackGenerateCli, PublicLayoutOptionsGiveLoadableLayouts) {
  std::string plain, log;
  ASSERT_EQ(test::run_fsd("track generate --seed 7 2>/dev/null", &plain), 0);
  const std::string file = test::scratch_path("cli_public.csv");
  for (const std::string flags : {"--share-hairpin-chain 0.15", "--circle", "--cone-jitter 0.25",
                                  "--spacing-jitter 0.3", "--inner-outlier 0.3", "--narrowing 2.85", "--irregular"}) {
    SCOPED_TRACE(flags);
    ASSERT_EQ(test::run_fsd("track generate --seed 7 " + flags + " --out " + file, &log), 0) << log;
    EXPECT_NE(slurp(file), plain);
    const Track t = load_track(file);
    if (flags == "--circle") {
      EXPECT_GE(t.count(ConeRole::Left) + t.count(ConeRole::Right), 13u);
      EXPECT_LE(t.count(ConeRole::Left) + t.count(ConeRole::Right), 20u);
      EXPECT_EQ(t.count(ConeRole::Timing), 0u);
    } else {
      EXPECT_GT(t.count(ConeRole::Left), 10u);
      EXPECT_EQ(t.count(ConeRole::Timing), 4u);
    }
  }
  std::string again;
  ASSERT_EQ(test::run_fsd("track generate --seed 7 --irregular 2>/dev/null", &again), 0);
  EXPECT_EQ(again, slurp(file));
}

TEST(TrackGenerateCli, BadOptionsExitTwoNamingWhatIsWrong) {
  struct Bad {
    const char* args;
    const char* says;
  };
  for (const Bad& c :
       {Bad{"--seed 1 --width 2.5", "3 m minimum"}, Bad{"--seed 1 --kind endurance", "endurance"},
        Bad{"--seed 1 --cone-spacing 6", "5 m maximum"}, Bad{"--seed 1 --kind skidpad --open", "--open"},
        Bad{"--seed 1 --kind acceleration --braking-length 120", "100 m"}, Bad{"--kind trackdrive", "--seed"},
        Bad{"--seed x", "--seed"}, Bad{"--seed 1 --cone-jitter 0.7", "cone jitter"},
        Bad{"--seed 1 --spacing-jitter 0.9", "spacing jitter"}, Bad{"--seed 1 --inner-outlier 2", "inner outlier"},
        Bad{"--seed 1 --narrowing 3.5", "narrowing"}, Bad{"--seed 1 --share-hairpin-chain -1", "hairpin chain"},
        Bad{"--seed 1 --kind acceleration --circle", "circle"}}) {
    std::string log;
    EXPECT_EQ(test::run_fsd(std::string("track generate ") + c.args, &log), 2) << c.args << "\n" << log;
    EXPECT_NE(log.find(c.says), std::string::npos) << c.args << "\n" << log;
  }
}

}  // namespace
}  // namespace fsd
