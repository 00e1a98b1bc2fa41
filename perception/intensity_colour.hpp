#pragma once
// Stage 6, beyond the paper: a cone's colour from the LiDAR's calibrated reflectivity along its height, for close
// cones and when the camera is down. FSG cones carry a stripe across the middle of their height: white on blue
// cones (brighter than the dark blue body), black on yellow ones (darker than the yellow body); orange cones white
// stripes on a body brighter than blue. The stripe/body contrast is independent of the sensor's gain and of the
// incidence angle; the body level alone (calibrated reflectivity) separates dark blue from bright yellow when no
// laser crossed the stripe. A big cone (by its height) is big orange when its white stripes show brighter than its
// body, or, when no laser crossed a stripe, when its body lies between dark blue and bright yellow plastic (every
// rule set's big cones are orange). Anything ambiguous is Unknown: a wrong colour costs more than none.
// Beyond `max_range` (one laser crosses a cone, low on it), up to `far_range`: the lower body alone, from the returns
// that lie below the stripe (FSG: 38 % of the height) by more than the laser's footprint and the ground's
// uncertainty there (`far_margin_per_m` × range) and above the ground threshold (`far_min_height`: grass reflects as
// brightly as yellow paint): dark blue or bright yellow plastic, as one paint (no return as bright as a white stripe,
// few as dark as blue for yellow: accumulated frames' heights can be centimetres off at that range), else Unknown.
#include <vector>

#include "common/config.hpp"
#include "common/types.hpp"
#include "perception/candidate.hpp"
#include "perception/ground_surface.hpp"

namespace fsd {

struct IntensityColourConfig {
  bool enabled = true;
  double max_range = 8.0;                        // m: farther, the lower body's level alone (too few lasers)
  double far_range = 20.0;                       // m: farther cones stay Unknown
  double far_margin_per_m = 0.002;               // m per m of range below the stripe (beam 1.5 mrad + ground)
  double far_min_height = 0.05;                  // m: lower returns may be the ground's (the ground threshold τ)
  double far_white_min = 80.0;                   // a return this bright is a white stripe: heights off, no colour
  double stripe_low = 0.42, stripe_high = 0.58;  // band of the small cone's height read as stripe (FSG: 0.38-0.62)
  double body_low = 0.32, body_high = 0.68;      // below / above: body
  // The big (orange) cone's two white stripes (FSG: 0.28-0.40 and 0.58-0.70 of its height), read shrunk by 0.02;
  // its body is the rest, 0.04 away from a stripe.
  double big_stripe1_low = 0.30, big_stripe1_high = 0.38, big_stripe2_low = 0.60, big_stripe2_high = 0.68;
  double big_bright_contrast = 1.35;  // white on orange is less contrast than white on blue
  double bright_contrast = 1.8;       // stripe/body reflectivity above this: a white stripe (blue or orange cone)
  double dark_contrast = 0.55;        // below this: a black stripe (yellow cone)
  double blue_body_max = 35.0;        // body reflectivity (upper quartile) at most this: dark blue plastic
  double blue_body_min = 12.0;        // with no stripe seen, a body darker than this is black (a tyre), not blue
  double yellow_body_min = 62.0;      // at least this, with no stripe seen: yellow
  double dark_stripe_max = 20.0;      // a stripe this dark with no body seen: black (yellow cone)
  int min_band_points = 2;            // points needed in a band to use it (twice that for the body alone)
  int min_points = 6;                 // a smaller cluster is too little to read a colour from
  // Every cone's body paint (blue, yellow, orange, red) reflects more than black rubber: a cluster whose body-band
  // returns are all darker than `black_max` is a tyre or a tyre stack, not a cone, at any range. Set below
  // `blue_body_min` (a dark, dirty or grazed blue body that the colour leaves Unknown is still a cone). The levels
  // are the VLP-16's calibrated reflectivity: off for clouds whose intensity has another scale (`fsd detect` on CSV).
  bool reject_black = true;
  double black_max = 8.0;
};
const ConfigSection<IntensityColourConfig>& intensity_colour_section();  // "perception.lidar.colour"

struct IntensityColour {
  ConeColour colour = ConeColour::Unknown;
  double confidence = 0.0;
};

class IntensityColourClassifier {
 public:
  IntensityColourClassifier(const IntensityColourConfig& cfg = {}, double small_height = 0.325,
                            double big_height = 0.505)
      : cfg_(cfg), small_height_(small_height), big_height_(big_height) {}
  IntensityColour classify(const ConeCandidate& cone, const GroundSurface& ground) const;
  // Black rubber: at least 2 × min_band_points returns in the body bands (the small cone's; a yellow cone's black
  // stripe is not judged) and none of them as bright as `black_max`. Independent of `enabled` and `max_range`.
  bool black(const ConeCandidate& cone, const GroundSurface& ground) const;
  const IntensityColourConfig& config() const { return cfg_; }

 private:
  IntensityColour far_body(const ConeCandidate& cone, const GroundSurface& ground) const;
  IntensityColourConfig cfg_;
  double small_height_, big_height_;
};

}  // namespace fsd
