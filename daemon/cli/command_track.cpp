// `fsd track generate`: a layout within the Formula Student Driverless rules from a seed, in the shared track
// CSV format (drivers/sim/track_generator, docs/track-generator.md); options add what public layouts have beyond
// the rules.
#include <cstdio>
#include <fstream>
#include <iostream>
#include <stdexcept>
#include <string>

#include <CLI/CLI.hpp>

#include "common/track.hpp"
#include "daemon/cli/cli.hpp"
#include "daemon/cli/commands.hpp"
#include "drivers/sim/track_generator/track_generator.hpp"

namespace fsd {

namespace {

struct GenerateArgs {
  std::uint64_t seed = 1;
  std::string kind = "trackdrive", out;
  std::optional<double> width, spacing, braking;
  sim::TrackGeneratorOptions options;
};

// Writes the file, or stdout without --out.
int generate(GenerateArgs& a) {
  sim::TrackGeneratorOptions& o = a.options;
  const auto kind = sim::layout_kind_from_string(a.kind);
  if (!kind)
    throw std::invalid_argument("--kind: unknown kind '" + a.kind + "' (trackdrive, autocross, acceleration, skidpad)");
  o.kind = *kind;
  o.seed = a.seed;
  if (o.open && o.kind != sim::LayoutKind::Trackdrive && o.kind != sim::LayoutKind::Autocross)
    throw std::invalid_argument("--open: only trackdrive and autocross layouts can be open");
  if (a.width) o.width_min = o.width_max = *a.width;
  if (a.spacing) o.spacing_min = o.spacing_max = *a.spacing;
  if (a.braking) o.braking_min = o.braking_max = *a.braking;
  const Track track = sim::generate_track(o);  // std::invalid_argument for bad options: exit 2 in run_cli
  const std::string text = format_track(track);
  if (a.out.empty()) {
    std::fwrite(text.data(), 1, text.size(), stdout);
    std::fflush(stdout);
    return kExitOk;
  }
  std::ofstream f(a.out, std::ios::binary);
  f << text;
  f.close();
  if (!f) {
    std::cerr << "fsd track generate: cannot write " << a.out << "\n";
    return kExitMissionFailed;
  }
  return kExitOk;
}

}  // namespace

void add_track_command(CLI::App& app, int& exit_code) {
  auto* track = app.add_subcommand("track", "track layouts");
  track->require_subcommand(1);
  auto* gen =
      track->add_subcommand("generate",
                            "a layout within the Formula Student Driverless rules, in the shared track CSV format "
                            "(docs/track-generator.md); the same seed and options give the same file");
  static GenerateArgs a;
  sim::TrackGeneratorOptions& o = a.options;
  sim::FeatureShares& sh = o.shares;
  gen->add_option("--seed", a.seed, "seed of the layout")->required();
  gen->add_option("--kind", a.kind, "trackdrive | autocross | acceleration | skidpad")->capture_default_str();
  gen->add_option("--out", a.out, "file to write (default: stdout)");
  gen->add_flag("--open", o.open, "trackdrive/autocross: an open course with separate start and finish lines");
  gen->add_option("--width", a.width, "track width, m (default: sampled from --width-min/--width-max)");
  gen->add_option("--width-min", o.width_min, "sampled track width from (the rules' minimum is 3 m)")
      ->capture_default_str();
  gen->add_option("--width-max", o.width_max, "sampled track width up to")->capture_default_str();
  gen->add_option("--cone-spacing", a.spacing, "largest gap between cones along a boundary, m (default: sampled)");
  gen->add_option("--cone-spacing-min", o.spacing_min, "sampled largest gap from")->capture_default_str();
  gen->add_option("--cone-spacing-max", o.spacing_max, "sampled largest gap up to (the rules' maximum is 5 m)")
      ->capture_default_str();
  gen->add_option("--turn-angle", o.turn_angle, "rad of boundary arc between cones in turns")->capture_default_str();
  gen->add_option("--separation", o.separation, "m between the boundaries of two parts of a loop")
      ->capture_default_str();
  gen->add_option("--lap-min", o.lap_min, "shortest centre line, m")->capture_default_str();
  gen->add_option("--lap-max", o.lap_max, "longest centre line, m")->capture_default_str();
  gen->add_option("--braking-length", a.braking, "acceleration: braking zone, m (default: sampled)");
  gen->add_option("--braking-min", o.braking_min, "sampled braking zone from")->capture_default_str();
  gen->add_option("--braking-max", o.braking_max, "sampled braking zone up to (the rules' 100 m)")
      ->capture_default_str();
  gen->add_option("--share-straight", sh.straight, "weight of straights")->capture_default_str();
  gen->add_option("--share-turn", sh.turn, "weight of constant turns")->capture_default_str();
  gen->add_option("--share-hairpin", sh.hairpin, "weight of hairpins")->capture_default_str();
  gen->add_option("--share-slalom", sh.slalom, "weight of slaloms")->capture_default_str();
  gen->add_option("--share-chicane", sh.chicane, "weight of chicanes")->capture_default_str();
  gen->add_option("--share-decreasing", sh.decreasing, "weight of decreasing-radius turns")->capture_default_str();
  gen->add_option("--share-straight-hairpin", sh.straight_hairpin, "weight of long straights into a hairpin")
      ->capture_default_str();
  // What public layouts have beyond the rules (docs/track-generator.md); trackdrive/autocross.
  gen->add_option("--share-hairpin-chain", sh.hairpin_chain,
                  "weight of chains of 2-3 minimum hairpins back to back (above 0: at least one per layout)")
      ->capture_default_str();
  gen->add_flag("--circle", o.circle, "the whole lap one turn at the rules' minimum (9 m, 3 m lane), car inside");
  gen->add_option("--cone-jitter", o.cone_jitter, "m each cone may stand off its place (placed by hand)")
      ->capture_default_str();
  gen->add_option("--spacing-jitter", o.spacing_jitter, "share by which gaps along a boundary may differ")
      ->capture_default_str();
  gen->add_option("--inner-outlier", o.inner_outlier, "m one inner cone of each tight turn stands into the lane")
      ->capture_default_str();
  gen->add_option("--narrowing", o.narrowing, "m the lane narrows to on one straight stretch (0: none)")
      ->capture_default_str();
  gen->add_flag("--irregular", o.irregular,
                "mix the classes above per seed (and a 25 m braking zone for acceleration); options given win");
  gen->callback([&exit_code] {
    try {
      exit_code = generate(a);
    } catch (const std::runtime_error& e) {
      std::cerr << "fsd track generate: " << e.what() << "\n";
      exit_code = kExitMissionFailed;
    }
  });
}

}  // namespace fsd
