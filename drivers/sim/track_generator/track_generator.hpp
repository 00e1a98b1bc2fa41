#pragma once
// Formula Student Driverless layouts made from a seed, for testing control on tracks it has never seen
// (`fsd track generate`, docs/track-generator.md). Pure: the same options give the same track on every run.
//   trackdrive / autocross: a closed loop of features (straights, constant turns, hairpins, slaloms, chicanes,
//     decreasing-radius turns, a long straight into a hairpin) closed by a smooth connection; candidates that
//     break a rule or come too near another part of themselves are thrown away and the next one is drawn.
//     `open` makes an autocross-style course with separate start and finish lines instead.
//   acceleration: the 75 m straight and a braking zone closed by a row of cones.
//   skidpad: the rules' figure of eight with its entry and exit lanes.
// Every constraint and the rule it comes from is listed in docs/track-generator.md. Options add what public
// layouts have and the rules-conforming defaults do not (hairpin chains, a whole-lap circle, hand-placed cones,
// a narrowing; `irregular` mixes them per seed); without them the defaults are unchanged.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "common/track.hpp"

namespace fsd::sim {

enum class LayoutKind : std::uint8_t { Trackdrive, Autocross, Acceleration, Skidpad };
std::string_view to_string(LayoutKind k);
std::optional<LayoutKind> layout_kind_from_string(std::string_view s);

// Relative weights of the features a loop is drawn from; 0 leaves a feature out.
struct FeatureShares {
  double straight = 0.22;
  double turn = 0.2;               // constant radius, up to the rules' 50 m outside diameter
  double hairpin = 0.12;           // about 180°, down to the rules' 9 m outside diameter
  double slalom = 0.1;             // a line of cones 7.5–12 m apart, passed on alternate sides
  double chicane = 0.12;           // two opposite bends
  double decreasing = 0.12;        // a turn that tightens as it goes
  double straight_hairpin = 0.12;  // a long straight (50–80 m) into a hairpin
  // 2–3 hairpins at the tightest radius, back to back with no straight between, alternating sides (150–190°
  // each). Above 0 every layout also holds at least one chain.
  double hairpin_chain = 0.0;
};

// Each range [min, max] is sampled once per layout; min == max fixes the value.
struct TrackGeneratorOptions {
  LayoutKind kind = LayoutKind::Trackdrive;
  std::uint64_t seed = 1;
  bool open = false;       // trackdrive/autocross: an open course (start and finish lines apart)
  double width_min = 3.0;  // m; the rules' minimum, and 40 % of sampled layouts sit at width_min
  double width_max = 5.0;
  double spacing_min = 3.0;  // m: largest gap between neighbouring cones along a boundary;
  double spacing_max = 5.0;  //    the rules allow at most 5 m; half the layouts sit at spacing_max
  double turn_angle = 0.45;  // rad of boundary arc between cones in turns, so tight turns get denser cones
  double separation = 2.0;   // m between the boundaries of two different parts of a loop
  double lap_min = 200.0, lap_max = 500.0;         // m of centre line (the rules' trackdrive lap)
  double braking_min = 30.0, braking_max = 100.0;  // acceleration: m from the finish line to the closing row
  FeatureShares shares;
  int max_attempts = 4000;  // candidate loops drawn before giving up

  // What public layouts have beyond the rules (docs/track-generator.md); trackdrive/autocross only.
  bool circle = false;          // the whole lap one turn at the rules' minimum (9 m outside, 3 m lane), car inside
  double cone_jitter = 0.0;     // m: each cone moved up to this far off its place, as cones placed by hand
  double spacing_jitter = 0.0;  // share: gaps along a boundary up to this share longer or shorter than even
  double inner_outlier = 0.0;   // m: in each tight turn one inner cone this far out of its ring, into the lane
  double narrowing = 0.0;       // m: one stretch per lap where the lane narrows to this width (under 3 m); 0 none
  // Each class above (and, for acceleration, a braking zone of 25 m) switched on per seed with its probability;
  // a class whose option is not at its default keeps that value for every seed.
  bool irregular = false;
};

// Throws std::invalid_argument naming the option that is out of range.
void validate(const TrackGeneratorOptions& options);

// The options a seed is generated with: `options` itself without `irregular`; with it, each class whose option
// is at its default is switched on or not by the seed's own draws (a stream of its own, so the layouts without
// `irregular` are untouched). The result has `irregular` false.
TrackGeneratorOptions resolve_mix(const TrackGeneratorOptions& options);

// The layout (name "generated_<kind>_<seed>") of resolve_mix(options); validates first. Throws
// std::runtime_error when no candidate of max_attempts met every constraint (options that leave too little room,
// e.g. a very short lap with only hairpins).
Track generate_track(const TrackGeneratorOptions& options);

}  // namespace fsd::sim
