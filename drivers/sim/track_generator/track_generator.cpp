#include "drivers/sim/track_generator/track_generator.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <stdexcept>
#include <utility>

#include "drivers/sim/track_generator/track_generator_detail.hpp"

namespace fsd::sim {

std::string_view to_string(LayoutKind k) {
  switch (k) {
    case LayoutKind::Trackdrive:
      return "trackdrive";
    case LayoutKind::Autocross:
      return "autocross";
    case LayoutKind::Acceleration:
      return "acceleration";
    case LayoutKind::Skidpad:
      return "skidpad";
  }
  return "trackdrive";
}

std::optional<LayoutKind> layout_kind_from_string(std::string_view s) {
  for (auto k : {LayoutKind::Trackdrive, LayoutKind::Autocross, LayoutKind::Acceleration, LayoutKind::Skidpad})
    if (s == to_string(k)) return k;
  return std::nullopt;
}

namespace {

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("track generator: " + what);
}

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

bool is_loop(LayoutKind k) { return k == LayoutKind::Trackdrive || k == LayoutKind::Autocross; }

// The irregular mix (issue 31's public layouts): the probability of each class per seed and its value.
constexpr double kMixChain = 0.5, kMixChainShare = 0.15;
constexpr double kMixJitter = 0.5, kMixConeJitter = 0.25;         // m
constexpr double kMixSpacing = 0.5, kMixSpacingJitter = 0.3;      // share
constexpr double kMixOutlier = 0.5, kMixInnerOutlier = 0.3;       // m
constexpr double kMixNarrowing = 0.4, kMixNarrowingWidth = 2.85;  // m
constexpr double kMixCircle = 0.05;
constexpr double kMixBraking = 0.35, kMixBrakingZone = 25.0;  // m: a braking zone closed 25 m after the finish

// The classes that bend the rules: their ranges, and only where they mean something.
void validate_irregular(const TrackGeneratorOptions& o) {
  for (double v : {o.cone_jitter, o.spacing_jitter, o.inner_outlier, o.narrowing})
    require(std::isfinite(v), "options must be finite numbers");
  require(o.cone_jitter >= 0.0 && o.cone_jitter <= 0.5, "cone jitter " + num(o.cone_jitter) + " m is outside 0–0.5 m");
  // Room for the jitter inside the rules' 5 m gaps: the even spacing shrinks by twice the jitter.
  require(o.spacing_min - 2.0 * o.cone_jitter >= 1.0,
          "cone jitter " + num(o.cone_jitter) + " m leaves under 1 m of cone spacing min " + num(o.spacing_min) + " m");
  require(o.spacing_jitter >= 0.0 && o.spacing_jitter <= 0.5,
          "spacing jitter " + num(o.spacing_jitter) + " is outside 0–0.5 (a share of the gap)");
  require(o.inner_outlier == 0.0 || (o.inner_outlier >= 0.05 && o.inner_outlier <= 1.0),
          "inner outlier " + num(o.inner_outlier) + " m must be 0 (none) or 0.05–1 m");
  require(o.narrowing == 0.0 || (o.narrowing >= 2.0 && o.narrowing < 3.0),
          "narrowing " + num(o.narrowing) + " m must be 0 (none) or 2–3 m (under the rules' 3 m lane)");
  const std::pair<bool, const char*> loop_only[] = {{o.circle, "circle"},
                                                    {o.shares.hairpin_chain > 0.0, "hairpin chain share"},
                                                    {o.cone_jitter > 0.0, "cone jitter"},
                                                    {o.spacing_jitter > 0.0, "spacing jitter"},
                                                    {o.inner_outlier > 0.0, "inner outlier"},
                                                    {o.narrowing > 0.0, "narrowing"}};
  for (const auto& [given, name] : loop_only)
    require(is_loop(o.kind) || !given, std::string(name) + " applies to trackdrive and autocross layouts only");
  require(!(o.circle && o.open), "circle: the whole-lap circle is a closed loop, it cannot be open");
}

}  // namespace

void validate(const TrackGeneratorOptions& o) {
  const auto finite = [](double v) { return std::isfinite(v); };
  for (double v : {o.width_min, o.width_max, o.spacing_min, o.spacing_max, o.turn_angle, o.separation, o.lap_min,
                   o.lap_max, o.braking_min, o.braking_max})
    require(finite(v), "options must be finite numbers");
  require(o.width_min >= 3.0, "track width " + num(o.width_min) + " m is below the rules' 3 m minimum");
  require(o.width_max >= o.width_min,
          "width max " + num(o.width_max) + " m is below width min " + num(o.width_min) + " m");
  require(o.width_max <= 8.0, "track width " + num(o.width_max) + " m is over the generator's 8 m maximum");
  require(o.spacing_max <= 5.0, "cone spacing " + num(o.spacing_max) + " m is over the rules' 5 m maximum");
  require(o.spacing_min >= 1.0, "cone spacing " + num(o.spacing_min) + " m is below the generator's 1 m minimum");
  require(o.spacing_max >= o.spacing_min,
          "cone spacing max " + num(o.spacing_max) + " m is below spacing min " + num(o.spacing_min) + " m");
  require(o.turn_angle >= 0.1 && o.turn_angle <= 1.0, "turn angle " + num(o.turn_angle) + " rad is outside 0.1–1");
  require(o.separation >= 1.0 && o.separation <= 10.0, "separation " + num(o.separation) + " m is outside 1–10 m");
  require(o.lap_min >= 200.0, "lap length " + num(o.lap_min) + " m is below the rules' 200 m");
  require(o.lap_max <= 500.0, "lap length " + num(o.lap_max) + " m is over the rules' 500 m");
  require(o.lap_max - o.lap_min >= 20.0,
          "lap length range " + num(o.lap_min) + "–" + num(o.lap_max) + " m is narrower than 20 m");
  require(o.braking_min >= 10.0, "braking zone " + num(o.braking_min) + " m is shorter than 10 m");
  require(o.braking_max <= 100.0, "braking zone " + num(o.braking_max) + " m is over the rules' 100 m");
  require(o.braking_max >= o.braking_min,
          "braking zone max " + num(o.braking_max) + " m is below min " + num(o.braking_min) + " m");
  const FeatureShares& s = o.shares;
  double sum = 0;
  for (double v : {s.straight, s.turn, s.hairpin, s.slalom, s.chicane, s.decreasing, s.straight_hairpin}) {
    require(finite(v) && v >= 0.0, "feature shares must be finite and not negative");
    sum += v;
  }
  require(finite(s.hairpin_chain) && s.hairpin_chain >= 0.0 && s.hairpin_chain <= 10.0,
          "hairpin chain share " + num(s.hairpin_chain) + " is outside 0–10");
  require(sum > 0.0, "at least one feature share must be positive");
  require(s.turn + s.hairpin + s.decreasing + s.straight_hairpin > 0.0,
          "a loop needs a turning feature (turn, hairpin, decreasing or straight_hairpin)");
  require(o.max_attempts >= 1 && o.max_attempts <= 100000, "max attempts must be 1–100000");
  validate_irregular(o);
}

TrackGeneratorOptions resolve_mix(const TrackGeneratorOptions& o) {
  TrackGeneratorOptions r = o;
  r.irregular = false;
  if (!o.irregular) return r;
  // A stream of its own, and every draw made whatever is switched on, so each class's draw is the same for a
  // seed whatever the others do.
  Rng rng(hash64(o.seed, 0x400 + static_cast<std::uint64_t>(o.kind), o.open ? 1 : 0));
  const bool chain = rng.chance(kMixChain), jitter = rng.chance(kMixJitter), spacing = rng.chance(kMixSpacing),
             outlier = rng.chance(kMixOutlier), narrowing = rng.chance(kMixNarrowing), circle = rng.chance(kMixCircle),
             braking = rng.chance(kMixBraking);
  const TrackGeneratorOptions d;  // the defaults: a class at its default is the mix's to switch
  if (is_loop(o.kind)) {
    if (chain && o.shares.hairpin_chain == d.shares.hairpin_chain) r.shares.hairpin_chain = kMixChainShare;
    if (jitter && o.cone_jitter == d.cone_jitter) r.cone_jitter = kMixConeJitter;
    if (spacing && o.spacing_jitter == d.spacing_jitter) r.spacing_jitter = kMixSpacingJitter;
    if (outlier && o.inner_outlier == d.inner_outlier) r.inner_outlier = kMixInnerOutlier;
    if (narrowing && o.narrowing == d.narrowing) r.narrowing = kMixNarrowingWidth;
    if (circle && !o.open) r.circle = true;
  } else if (o.kind == LayoutKind::Acceleration) {
    if (braking && o.braking_min == d.braking_min && o.braking_max == d.braking_max)
      r.braking_min = r.braking_max = kMixBrakingZone;
  }
  return r;
}

Track generate_track(const TrackGeneratorOptions& options) {
  validate(options);
  const TrackGeneratorOptions o = resolve_mix(options);
  validate(o);  // the mix's values within what the other options leave room for
  Track t;
  switch (o.kind) {
    case LayoutKind::Trackdrive:
    case LayoutKind::Autocross:
      t = o.circle ? detail::generate_circle(o) : detail::generate_loop(o);
      break;
    case LayoutKind::Acceleration:
      t = detail::generate_acceleration(o);
      break;
    case LayoutKind::Skidpad:
      t = detail::generate_skidpad(o);
      break;
  }
  t.name = "generated_" + std::string(to_string(o.kind)) + (o.open ? "_open_" : "_") + std::to_string(o.seed);
  return t;
}

namespace detail {

double sample_range(Rng& rng, double lo, double hi, double edge_share, double edge) {
  const double u = rng.uniform();  // always one draw, so later draws do not depend on the range
  const double v = rng.uniform(lo, hi);
  return (hi <= lo || u < edge_share) ? edge : v;
}

void add_cone(Track& track, ConeRole role, const Vec2& p) {
  TrackCone c;
  c.position = p;
  c.role = role;
  c.colour = track.convention.colour_of(role);
  track.cones.push_back(c);
}

std::vector<Vec2> place_cones(const std::vector<Vec2>& line, const std::vector<double>& spacing, bool closed,
                              std::vector<std::size_t> anchors) {
  std::vector<Vec2> out;
  for (const PlacedCone& c : place_cones_along(line, spacing, closed, std::move(anchors))) out.push_back(c.p);
  return out;
}

std::vector<PlacedCone> place_cones_along(const std::vector<Vec2>& line, const std::vector<double>& spacing,
                                          bool closed, std::vector<std::size_t> anchors, double spacing_jitter,
                                          Rng* rng) {
  const std::size_t n = line.size();
  std::vector<PlacedCone> out;
  if (n < 2) return out;
  // Arc length, and the spacing each point may have: the smallest asked within one spacing either side, so a
  // gap that starts on a straight and ends in a turn is already a turn's gap.
  std::vector<double> s(n + 1, 0.0);
  for (std::size_t i = 1; i <= n; ++i) {
    const std::size_t j = i % n;
    s[i] = s[i - 1] + (i < n || closed ? (line[j] - line[i - 1]).norm() : 0.0);
  }
  std::vector<double> eff(n);
  for (std::size_t i = 0; i < n; ++i) {
    double m = spacing[i];
    for (int dir : {-1, 1}) {
      double run = 0;
      std::size_t k = i;
      for (std::size_t step = 0; step < n && run < spacing[i]; ++step) {
        const std::size_t next = dir > 0 ? (k + 1) % n : (k + n - 1) % n;
        if (!closed && ((dir > 0 && k + 1 >= n) || (dir < 0 && k == 0))) break;
        run += (line[next] - line[k]).norm();
        k = next;
        m = std::min(m, spacing[k]);
      }
    }
    eff[i] = m;
  }
  // "Cone density" u: one unit per spacing; cones go at equal steps of u between anchors, so every gap is
  // within the spacing asked along it.
  std::vector<double> u(n + 1, 0.0);
  for (std::size_t i = 1; i <= n; ++i) u[i] = u[i - 1] + (s[i] - s[i - 1]) / eff[(i - 1) % n];
  auto at_u = [&](double q) {
    const auto it = std::upper_bound(u.begin(), u.end(), q);
    std::size_t i = static_cast<std::size_t>(std::max<std::ptrdiff_t>(1, it - u.begin())) - 1;
    i = std::min(i, n - 1);
    const double span = u[i + 1] - u[i];
    const double f = span > 0 ? std::clamp((q - u[i]) / span, 0.0, 1.0) : 0.0;
    return PlacedCone{Vec2(line[i] + f * (line[(i + 1) % n] - line[i])), i};
  };
  if (!closed) {
    if (anchors.empty() || anchors.front() != 0) anchors.insert(anchors.begin(), 0);
    if (anchors.back() != n - 1) anchors.push_back(n - 1);
  } else if (anchors.empty()) {
    anchors.push_back(0);
  }
  const bool uneven = spacing_jitter > 0.0 && rng;
  const std::size_t segments = closed ? anchors.size() : anchors.size() - 1;
  for (std::size_t a = 0; a < segments; ++a) {
    const double u0 = u[anchors[a]];
    double u1 = a + 1 < anchors.size() ? u[anchors[a + 1]] : u[n] + u[anchors.front()];
    const double span = u1 - u0;
    const int gaps = std::max(1, static_cast<int>(std::ceil(span - 1e-9)));
    for (int k = 0; k < gaps; ++k) {
      // The anchor stays; each cone after it moves by up to half the jitter's share of a gap either way.
      const double shift = uneven && k > 0 ? spacing_jitter * (rng->uniform() - 0.5) : 0.0;
      double q = u0 + span * (k + shift) / gaps;
      if (q >= u[n]) q -= u[n];
      out.push_back(at_u(q));
    }
  }
  if (!closed) out.push_back({line.back(), n - 1});
  return out;
}

Vec2 hand_offset(Rng& rng, double jitter, double inward_room) {
  const double r = jitter * std::sqrt(rng.uniform()), a = 2.0 * std::numbers::pi * rng.uniform();
  Vec2 d(r * std::cos(a), r * std::sin(a));
  if (-d.y() > inward_room) d.y() = -d.y();
  return d;
}

}  // namespace detail
}  // namespace fsd::sim
