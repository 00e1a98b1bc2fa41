#include "perception/intensity_colour.hpp"

#include <algorithm>

namespace fsd {

const ConfigSection<IntensityColourConfig>& intensity_colour_section() {
  static const auto s =
      ConfigSection<IntensityColourConfig>("perception.lidar.colour")
          .boolean("enabled", &IntensityColourConfig::enabled,
                   "Colour close cones from the LiDAR reflectivity pattern.")
          .number("max_range", &IntensityColourConfig::max_range, 0.0, 50.0, "m",
                  "Farther cones are named by their lower body's reflectivity alone (far_range).")
          .number("far_range", &IntensityColourConfig::far_range, 0.0, 50.0, "m",
                  "Beyond max_range up to this, a cone is named from the returns below its stripe (dark blue or "
                  "bright yellow); farther cones stay Unknown.")
          .number("far_min_height", &IntensityColourConfig::far_min_height, 0.0, 0.3, "m",
                  "Beyond max_range, returns lower than this may be the ground's (grass reflects as brightly as "
                  "yellow paint) and do not count (the ground threshold).")
          .number("far_white_min", &IntensityColourConfig::far_white_min, 0.0, 255.0, "",
                  "Beyond max_range, a return this bright among the lower body's is a white stripe: the heights are "
                  "off, no colour.")
          .number("far_margin_per_m", &IntensityColourConfig::far_margin_per_m, 0.0, 0.05, "m/m",
                  "Beyond max_range, a return counts as the lower body when it lies below the stripe by this times "
                  "its range (the laser's vertical footprint and the ground's uncertainty).")
          .number("stripe_low", &IntensityColourConfig::stripe_low, 0.0, 1.0, "",
                  "Lower edge of the stripe band, as a share of the small cone's height.")
          .number("stripe_high", &IntensityColourConfig::stripe_high, 0.0, 1.0, "", "Upper edge of the stripe band.")
          .number("big_stripe1_low", &IntensityColourConfig::big_stripe1_low, 0.0, 1.0, "",
                  "Big cone: lower white stripe's lower edge, as a share of its height.")
          .number("big_stripe1_high", &IntensityColourConfig::big_stripe1_high, 0.0, 1.0, "",
                  "Big cone: lower white stripe's upper edge.")
          .number("big_stripe2_low", &IntensityColourConfig::big_stripe2_low, 0.0, 1.0, "",
                  "Big cone: upper white stripe's lower edge.")
          .number("big_stripe2_high", &IntensityColourConfig::big_stripe2_high, 0.0, 1.0, "",
                  "Big cone: upper white stripe's upper edge.")
          .number("big_bright_contrast", &IntensityColourConfig::big_bright_contrast, 1.0, 100.0, "",
                  "Big cone: stripe/body reflectivity ratio above which its white stripes show (big orange).")
          .number("body_low", &IntensityColourConfig::body_low, 0.0, 1.0, "",
                  "Points below this share of the height are body.")
          .number("body_high", &IntensityColourConfig::body_high, 0.0, 1.0, "",
                  "Points above this share of the height are body.")
          .number("bright_contrast", &IntensityColourConfig::bright_contrast, 1.0, 100.0, "",
                  "Stripe/body reflectivity ratio above which the stripe is white (blue or orange cone).")
          .number("dark_contrast", &IntensityColourConfig::dark_contrast, 0.0, 1.0, "",
                  "Stripe/body reflectivity ratio below which the stripe is black (yellow cone).")
          .number("blue_body_max", &IntensityColourConfig::blue_body_max, 0.0, 255.0, "",
                  "Body reflectivity at most this is dark blue plastic.")
          .number("blue_body_min", &IntensityColourConfig::blue_body_min, 0.0, 255.0, "",
                  "With no stripe seen, a body darker than this is black (a tyre's rubber), not blue plastic.")
          .number("yellow_body_min", &IntensityColourConfig::yellow_body_min, 0.0, 255.0, "",
                  "Body reflectivity at least this, no stripe seen, is yellow plastic.")
          .number("dark_stripe_max", &IntensityColourConfig::dark_stripe_max, 0.0, 255.0, "",
                  "A stripe at most this bright, no body seen, is black (yellow cone).")
          .integer("min_band_points", &IntensityColourConfig::min_band_points, 1, 1000, "",
                   "Points needed in the stripe or body band to use it (twice that to name a colour from the body "
                   "alone).")
          .integer("min_points", &IntensityColourConfig::min_points, 1, 10000, "",
                   "Clusters with fewer points get no colour.")
          .boolean("reject_black", &IntensityColourConfig::reject_black,
                   "Reject a cluster whose body-band returns are all darker than black_max (black rubber: tyres, "
                   "tyre stacks) as no cone, at any range. Calibrated VLP-16 reflectivity only.")
          .number("black_max", &IntensityColourConfig::black_max, 0.0, 255.0, "",
                  "Body reflectivity below this is black rubber (reject_black); below blue_body_min, so that a dark "
                  "blue body is not rejected.");
  return s;
}

namespace {

// Upper quartile: the points facing the sensor squarely (incidence dims the others).
double upper_quartile(std::vector<double>& v) {
  const auto k = v.size() * 3 / 4;
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
  return v[k];
}

}  // namespace

IntensityColour IntensityColourClassifier::far_body(const ConeCandidate& cone, const GroundSurface& ground) const {
  // FSG's stripe starts at 38 % of a small cone's height; the lower body is what lies surely below it.
  constexpr double kStripeLowerEdge = 0.38;
  if (cone.big || cone.range > cfg_.far_range) return {};
  const double below = kStripeLowerEdge * small_height_ - cfg_.far_margin_per_m * cone.range;
  std::vector<double> body;
  for (const auto& q : cone.cloud)
    if (const double h = ground.height_of(q.x, q.y, q.z); h < below && h > cfg_.far_min_height)
      body.push_back(q.intensity);
  if (body.size() < 2 * static_cast<std::size_t>(cfg_.min_band_points)) return {};
  // One paint, or no colour: a return as bright as a white stripe means the heights are off (the stripe is among
  // them: a blue or an orange cone); a yellow body has few returns as dark as blue plastic (its grazing edge).
  if (*std::max_element(body.begin(), body.end()) >= cfg_.far_white_min) return {};
  const auto dark = std::count_if(body.begin(), body.end(), [&](double v) { return v <= cfg_.blue_body_max; });
  const double b = upper_quartile(body);
  if (b <= cfg_.blue_body_max && b >= cfg_.blue_body_min) return {ConeColour::Blue, 0.5};
  if (b >= cfg_.yellow_body_min && 4 * dark <= static_cast<std::ptrdiff_t>(body.size()))
    return {ConeColour::Yellow, 0.5};
  return {};
}

IntensityColour IntensityColourClassifier::classify(const ConeCandidate& cone, const GroundSurface& ground) const {
  IntensityColour out;
  if (!cfg_.enabled) return out;
  if (cone.range > cfg_.max_range) return far_body(cone, ground);
  if (cone.cloud.size() < static_cast<std::size_t>(cfg_.min_points)) return out;
  std::vector<double> stripe, body;
  const auto need = static_cast<std::size_t>(cfg_.min_band_points);
  if (cone.big) {
    // Only timing cones are big; still, their stripes must show when a laser crossed them.
    const auto in = [](double f, double lo, double hi) { return f >= lo && f <= hi; };
    for (const auto& q : cone.cloud) {
      const double f = ground.height_of(q.x, q.y, q.z) / big_height_;
      if (in(f, cfg_.big_stripe1_low, cfg_.big_stripe1_high) || in(f, cfg_.big_stripe2_low, cfg_.big_stripe2_high))
        stripe.push_back(q.intensity);
      else if (f < cfg_.big_stripe1_low - 0.06 || in(f, cfg_.big_stripe1_high + 0.06, cfg_.big_stripe2_low - 0.06) ||
               f > cfg_.big_stripe2_high + 0.06)
        body.push_back(q.intensity);
    }
    if (stripe.size() < need) {
      // No laser crossed a stripe (two lasers at ~7 m can both miss them). Big cones are orange in every rule set,
      // so a body between dark blue and bright yellow plastic names it; tyres, dark stacks and bright posts do not.
      if (body.size() < 2 * need) return out;
      const double b = upper_quartile(body);
      return b > cfg_.blue_body_max && b < cfg_.yellow_body_min ? IntensityColour{ConeColour::BigOrange, 0.6} : out;
    }
    if (body.size() < need) return out;
    const double contrast = upper_quartile(stripe) / std::max(1.0, upper_quartile(body));
    return contrast >= cfg_.big_bright_contrast ? IntensityColour{ConeColour::BigOrange, 0.9} : out;
  }
  for (const auto& q : cone.cloud) {
    const double f = ground.height_of(q.x, q.y, q.z) / small_height_;
    if (f >= cfg_.stripe_low && f <= cfg_.stripe_high)
      stripe.push_back(q.intensity);
    else if (f < cfg_.body_low || f > cfg_.body_high)
      body.push_back(q.intensity);
  }
  const bool have_stripe = stripe.size() >= need, have_body = body.size() >= need;
  if (have_stripe && have_body) {
    const double s = upper_quartile(stripe), b = std::max(1.0, upper_quartile(body));
    const double contrast = s / b;
    if (contrast >= cfg_.bright_contrast)
      return b <= cfg_.blue_body_max ? IntensityColour{ConeColour::Blue, 0.9}
                                     : IntensityColour{ConeColour::Orange, 0.7};
    if (contrast <= cfg_.dark_contrast) return {ConeColour::Yellow, 0.9};
    return out;
  }
  if (body.size() >= 2 * need) {
    const double b = upper_quartile(body);
    // Dark, but not black: a tyre's rubber reflects less than blue plastic, and a body alone shows no stripe.
    if (b <= cfg_.blue_body_max && b >= cfg_.blue_body_min) return {ConeColour::Blue, 0.6};
    if (b >= cfg_.yellow_body_min) return {ConeColour::Yellow, 0.6};
    return out;
  }
  if (have_stripe && upper_quartile(stripe) <= cfg_.dark_stripe_max) return {ConeColour::Yellow, 0.6};
  return out;
}

bool IntensityColourClassifier::black(const ConeCandidate& cone, const GroundSurface& ground) const {
  std::size_t body = 0;
  for (const auto& q : cone.cloud) {
    const double f = ground.height_of(q.x, q.y, q.z) / small_height_;
    if (f >= cfg_.body_low && f <= cfg_.body_high) continue;  // a yellow cone's stripe is black paint
    if (q.intensity >= cfg_.black_max) return false;
    ++body;
  }
  return body >= 2 * static_cast<std::size_t>(cfg_.min_band_points);
}

}  // namespace fsd
