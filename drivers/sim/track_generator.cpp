#include "drivers/sim/track_generator.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "drivers/sim/track_generator_detail.hpp"

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
  require(sum > 0.0, "at least one feature share must be positive");
  require(s.turn + s.hairpin + s.decreasing + s.straight_hairpin > 0.0,
          "a loop needs a turning feature (turn, hairpin, decreasing or straight_hairpin)");
  require(o.max_attempts >= 1 && o.max_attempts <= 100000, "max attempts must be 1–100000");
}

Track generate_track(const TrackGeneratorOptions& o) {
  validate(o);
  Track t;
  switch (o.kind) {
    case LayoutKind::Trackdrive:
    case LayoutKind::Autocross:
      t = detail::generate_loop(o);
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
  const std::size_t n = line.size();
  std::vector<Vec2> out;
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
    return Vec2(line[i] + f * (line[(i + 1) % n] - line[i]));
  };
  if (!closed) {
    if (anchors.empty() || anchors.front() != 0) anchors.insert(anchors.begin(), 0);
    if (anchors.back() != n - 1) anchors.push_back(n - 1);
  } else if (anchors.empty()) {
    anchors.push_back(0);
  }
  const std::size_t segments = closed ? anchors.size() : anchors.size() - 1;
  for (std::size_t a = 0; a < segments; ++a) {
    const double u0 = u[anchors[a]];
    double u1 = a + 1 < anchors.size() ? u[anchors[a + 1]] : u[n] + u[anchors.front()];
    const double span = u1 - u0;
    const int gaps = std::max(1, static_cast<int>(std::ceil(span - 1e-9)));
    for (int k = 0; k < gaps; ++k) {
      double q = u0 + span * k / gaps;
      if (q >= u[n]) q -= u[n];
      out.push_back(at_u(q));
    }
  }
  if (!closed) out.push_back(line.back());
  return out;
}

}  // namespace detail
}  // namespace fsd::sim
