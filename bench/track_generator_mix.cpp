// The figures docs/track-generator.md quotes for `fsd track generate --irregular`: how often each class of public
// layouts shows over 200 seeds of trackdrive and of autocross, as the independent checker sees it from the cones
// (tests/sim/layout_rules.hpp), how often that disagrees with what the seed drew, and the time to generate; and
// how often an acceleration lane's braking zone is closed 25 m after the finish. Exits 1 when a figure is off its
// target (no disagreement; cone jitter 50 %, narrowing 40 %, circle 5 %, short braking zone 35 %, each within
// the tolerance below). Takes seconds. From the project root:
//   build/bench/track_generator_mix
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <string>

#include "common/track.hpp"
#include "drivers/sim/track_generator/track_generator.hpp"
#include "tests/scratch_dir.hpp"
#include "tests/sim/layout_rules.hpp"

namespace {

using fsd::sim::LayoutKind;

constexpr int kSeeds = 200;

// The layout of `kind` and `seed` with the mix on, as `fsd track generate --irregular` writes it.
fsd::sim::TrackGeneratorOptions irregular(LayoutKind kind, int seed) {
  fsd::sim::TrackGeneratorOptions o;
  o.kind = kind;
  o.seed = static_cast<std::uint64_t>(seed);
  o.irregular = true;
  return o;
}

// The layout written as a file and read back by the checker.
fsd::test::LayoutRows written(const std::string& text) {
  const std::string path = fsd::test::scratch_path("mix_figures.csv");
  std::ofstream(path, std::ios::binary) << text;
  return fsd::test::read_layout(path);
}

int failures = 0;

// A figure against its target: prints it when it is not met.
void expect_near(const char* what, double value, double target, double tolerance) {
  if (std::fabs(value - target) <= tolerance) return;
  ++failures;
  std::printf("NOT MET: %s %.3f, target %.3f +- %.3f\n", what, value, target, tolerance);
}

}  // namespace

int main() {
  for (auto kind : {LayoutKind::Trackdrive, LayoutKind::Autocross}) {
    const std::string name(fsd::sim::to_string(kind));
    int loops = 0, circles = 0, chains = 0, jittered = 0, unjittered = 0, uneven = 0, outliers = 0, narrowings = 0;
    int missed = 0, unasked_chains = 0;  // a class drawn but not seen (chains aside); chains seen but not drawn
    double seconds = 0, worst = 0;
    for (int seed = 1; seed <= kSeeds; ++seed) {
      const auto o = irregular(kind, seed);
      const auto r = fsd::sim::resolve_mix(o);
      const auto t0 = std::chrono::steady_clock::now();
      const std::string text = fsd::format_track(fsd::sim::generate_track(o));
      const double dt = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      seconds += dt, worst = std::max(worst, dt);
      const fsd::test::Seen s = fsd::test::seen_in(written(text), true);
      auto disagree = [&](bool seen, bool drawn, const char* what) {
        if (seen == drawn) return;
        ++missed;
        std::printf("  %s seed %d: %s %s but %s\n", name.c_str(), seed, what, drawn ? "drawn" : "not drawn",
                    seen ? "seen" : "not seen");
      };
      disagree(s.circle, r.circle, "circle");
      if (s.circle) {
        ++circles;
        continue;
      }
      ++loops;
      chains += s.chain, jittered += s.jittered, outliers += s.outlier, narrowings += s.narrowing;
      if (!s.jittered) {
        ++unjittered, uneven += s.uneven;
        disagree(s.uneven, r.spacing_jitter > 0, "spacing jitter");
      }
      disagree(s.jittered, r.cone_jitter > 0, "cone jitter");
      disagree(s.outlier, r.inner_outlier > 0, "inner outlier");
      disagree(s.narrowing, r.narrowing > 0, "narrowing");
      if (r.shares.hairpin_chain > 0) disagree(s.chain, true, "hairpin chain");
      unasked_chains += r.shares.hairpin_chain == 0 && s.chain;
    }
    std::printf(
        "%s, %d seeds: circle %d (%.1f %%); of the %d loops: hairpin chains %.1f %%, cone jitter %.1f %%, inner "
        "outlier %.1f %%, narrowing %.1f %%; uneven spacing %.1f %% of the %d without jitter. Seen against drawn: "
        "%d disagreements, %d layouts with chains not drawn. Generation %.1f ms mean, %.1f ms worst\n",
        name.c_str(), kSeeds, circles, 100.0 * circles / kSeeds, loops, 100.0 * chains / loops,
        100.0 * jittered / loops, 100.0 * outliers / loops, 100.0 * narrowings / loops, 100.0 * uneven / unjittered,
        unjittered, missed, unasked_chains, 1e3 * seconds / kSeeds, 1e3 * worst);
    expect_near((name + ": disagreements").c_str(), missed, 0, 0);
    expect_near((name + ": cone jitter share").c_str(), jittered / double(loops), 0.5, 0.1);
    expect_near((name + ": narrowing share").c_str(), narrowings / double(loops), 0.4, 0.1);
    expect_near((name + ": circle share").c_str(), circles / double(kSeeds), 0.05, 0.04);
  }
  int short_zones = 0;
  for (int seed = 1; seed <= kSeeds; ++seed) {
    const auto o = irregular(LayoutKind::Acceleration, seed);
    const double zone = fsd::test::braking_zone(written(fsd::format_track(fsd::sim::generate_track(o))));
    short_zones += std::fabs(zone - 25.0) < 0.01;
  }
  std::printf("acceleration, %d seeds: braking zone closed 25 m after the finish %.1f %%\n", kSeeds,
              100.0 * short_zones / kSeeds);
  expect_near("acceleration: short braking zone share", short_zones / double(kSeeds), 0.35, 0.1);
  return failures == 0 ? 0 : 1;
}
