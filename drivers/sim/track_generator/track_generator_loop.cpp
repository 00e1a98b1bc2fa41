// Trackdrive and autocross layouts: a centre line drawn feature by feature, closed by the shortest Dubins
// connection back to the start straight, then checked against the rules and the separation of its own parts;
// a candidate that fails is dropped and the next one drawn (docs/track-generator.md).
#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <optional>
#include <stdexcept>

#include "drivers/sim/track_generator/centre_line_builder.hpp"
#include "drivers/sim/track_generator/track_generator_detail.hpp"

namespace fsd::sim::detail {

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kDeg = kPi / 180.0;
constexpr double kTurnOuterMax = 25.0;                 // m: the rules' 50 m constant-turn diameter
constexpr double kStraightMax = 80.0;                  // m: the rules' longest straight
constexpr double kSlalomMin = 7.5, kSlalomMax = 12.0;  // m between slalom cones (the rules)
constexpr double kLapMargin = 5.0;                     // m inside the lap range: the chords between cones are shorter
constexpr double kRunOff = 30.0;     // m of free straight after an open course's finish (the stop zone)
constexpr double kBehindOpen = 4.0;  // m of boundary behind the car on an open course
constexpr double kChainAngleMin = 150.0, kChainAngleMax = 190.0;  // degrees of each hairpin of a chain

// HairpinChain last, so a share of 0 leaves the draws of the other features as they were.
enum class Feature { Straight, Turn, Hairpin, Slalom, Chicane, Decreasing, StraightHairpin, HairpinChain };

using Layout = LoopLayout;
using Candidate = LoopCandidate;

// The sign of a turn that keeps the heading near a steady progression to the total it must reach, most of
// the time (so loops close), and the other one otherwise (so they are not all round).
int pick_sign(Rng& rng, double cum, double angle, double target_now) {
  const int s = std::fabs(cum + angle - target_now) <= std::fabs(cum - angle - target_now) ? 1 : -1;
  return rng.chance(0.2) ? -s : s;
}

double slalom_min_spacing(double width, double rc_min) {
  // The wave y = A(1 − cos(πx/d)) bends at radius d²/(Aπ²) at its extremes; A is half the width.
  return std::max(kSlalomMin, kPi * std::sqrt(0.5 * width * rc_min));
}

Feature pick_feature(Rng& rng, const FeatureShares& sh, bool after_straight, bool slalom_ok) {
  const std::array<std::pair<Feature, double>, 8> w = {
      {{Feature::Straight, after_straight ? 0.0 : sh.straight},
       {Feature::Turn, sh.turn},
       {Feature::Hairpin, sh.hairpin},
       {Feature::Slalom, slalom_ok ? sh.slalom : 0.0},
       {Feature::Chicane, sh.chicane},
       {Feature::Decreasing, sh.decreasing},
       {Feature::StraightHairpin, after_straight ? 0.0 : sh.straight_hairpin},
       {Feature::HairpinChain, sh.hairpin_chain}}};
  double sum = 0;
  for (const auto& [f, v] : w) sum += v;
  double r = rng.uniform() * sum;
  for (const auto& [f, v] : w) {
    if (v <= 0) continue;
    if (r < v) return f;
    r -= v;
  }
  return Feature::Turn;
}

// An S of 2–3 hairpins at radius r: back to back, each turning the other way, 150–190° each. The first turns
// the way that keeps the chain's net turning near the heading's progression (as a single turn's sign).
template <typename TargetAt>
void hairpin_chain(CentreLineBuilder& b, Rng& rng, double r, double& cum, const TargetAt& target_at) {
  const int count = rng.uniform_int(2, 3);
  std::array<double, 3> angle{};
  double net = 0, len = 0;
  for (int k = 0; k < count; ++k) {
    angle[static_cast<std::size_t>(k)] = rng.uniform(kChainAngleMin, kChainAngleMax) * kDeg;
    net += (k % 2 == 0 ? 1.0 : -1.0) * angle[static_cast<std::size_t>(k)];
    len += r * angle[static_cast<std::size_t>(k)];
  }
  const int sign = pick_sign(rng, cum, net, target_at(b.length() + len));
  for (int k = 0; k < count; ++k) b.arc(r, (k % 2 == 0 ? sign : -sign) * angle[static_cast<std::size_t>(k)]);
  cum += sign * net;
}

std::optional<Candidate> draw(const TrackGeneratorOptions& o, const Layout& lay, Rng& rng) {
  const double w = lay.width, rc_min = lay.rc_min;
  const double length = rng.uniform(o.lap_min + kLapMargin, o.lap_max - kLapMargin);
  const int dir = rng.chance(0.5) ? 1 : -1;
  const double total_turn = o.open ? dir * rng.uniform(0.5, 1.5) * kPi : dir * 2.0 * kPi;
  const Vec2 fwd(std::cos(lay.yaw0), std::sin(lay.yaw0));
  const double behind = o.open ? kBehindOpen : rng.uniform(8.0, 25.0);  // start straight behind car_start
  const double ahead = rng.uniform(kStartLine + 6.0, 40.0);             // and ahead of it
  const Pose2 before{-behind * fwd.x(), -behind * fwd.y(), lay.yaw0};
  const double turn_lo = std::max(rc_min, 6.0), turn_hi = std::max(turn_lo, kTurnOuterMax - 0.5 * w);
  const double slalom_lo = slalom_min_spacing(w, rc_min);
  const double hairpin_lo = rc_min + 0.5 * w, hairpin_hi = std::max(hairpin_lo, 7.5);

  Candidate c;
  CentreLineBuilder b(o.open ? before : Pose2{0, 0, lay.yaw0});
  b.straight(o.open ? behind + ahead : ahead);
  c.start_s = o.open ? behind : 0.0;
  double cum = 0;  // signed turning so far
  bool after_straight = true;
  double last_straight = ahead;
  auto target_at = [&](double s) { return total_turn * s / length; };
  auto still_to_go = [&] { return o.open ? 25.0 : (b.end().position() - before.position()).norm() + 15.0; };
  while (b.length() + still_to_go() < length) {
    const Feature f = pick_feature(rng, o.shares, after_straight, slalom_lo <= kSlalomMax);
    after_straight = false;
    switch (f) {
      case Feature::Straight: {
        last_straight = rng.chance(0.2) ? rng.uniform(50.0, kStraightMax) : rng.uniform(10.0, 50.0);
        b.straight(last_straight);
        after_straight = true;
        break;
      }
      case Feature::Turn: {
        const double r = rng.uniform(turn_lo, turn_hi), a = rng.uniform(30.0, 180.0) * kDeg;
        const double sa = pick_sign(rng, cum, a, target_at(b.length() + r * a)) * a;
        b.arc(r, sa);
        cum += sa;
        break;
      }
      case Feature::StraightHairpin:
        b.straight(rng.uniform(50.0, kStraightMax));
        [[fallthrough]];
      case Feature::Hairpin: {
        // Half of the hairpins at the tightest the rules and the width allow.
        const double outer = sample_range(rng, hairpin_lo, hairpin_hi, 0.5, hairpin_lo);
        const double r = outer - 0.5 * w, a = rng.uniform(170.0, 190.0) * kDeg;
        const double sa = pick_sign(rng, cum, a, target_at(b.length() + r * a)) * a;
        b.arc(r, sa);
        cum += sa;
        break;
      }
      case Feature::Slalom: {
        const double d = rng.uniform(slalom_lo, kSlalomMax);
        const int n = rng.uniform_int(3, 6), side = rng.chance(0.5) ? 1 : -1;
        const auto extremes = b.slalom(d, n, 0.5 * w, side);
        // At even extremes the car is on the start side and the line of cones on its other side.
        for (std::size_t k = 0; k < extremes.size(); ++k) c.anchors.push_back({extremes[k], k % 2 == 0 ? -side : side});
        break;
      }
      case Feature::Chicane: {
        const double r = rng.uniform(turn_lo, std::max(turn_lo, 15.0)), a = rng.uniform(25.0, 60.0) * kDeg;
        const double sign = rng.chance(0.5) ? 1.0 : -1.0;
        b.arc(r, sign * a);
        b.straight(rng.uniform(0.0, 4.0));
        b.arc(r, -sign * a);
        break;
      }
      case Feature::Decreasing: {
        const double r1 = rng.uniform(std::max(12.0, rc_min + 4.0), std::max(std::max(12.0, rc_min + 4.0), turn_hi));
        const double r2 = rng.uniform(rc_min, std::max(rc_min, 0.6 * r1));
        const double a = rng.uniform(90.0, 180.0) * kDeg;
        const double len = 2.0 * a / (1.0 / r1 + 1.0 / r2);
        const double sign = pick_sign(rng, cum, a, target_at(b.length() + len));
        b.clothoid(sign / r1, sign / r2, len);
        cum += sign * a;
        break;
      }
      case Feature::HairpinChain:
        hairpin_chain(b, rng, rc_min, cum, target_at);
        ++c.chains;
        break;
    }
    if (b.length() > 2.0 * length) return std::nullopt;
  }
  if (o.open) {
    // A straight to the finish line, then the free run-off where the car stops.
    const double end = rng.uniform(20.0, 40.0);
    b.straight(after_straight ? std::max(0.0, std::min(end, kStraightMax - last_straight)) : end);
    c.end_s = b.length();
    b.straight(kRunOff);
  } else {
    if (!b.dubins_to(before, rng.uniform(turn_lo, turn_hi))) return std::nullopt;
    b.straight(behind);
  }
  c.line = b.samples();
  if (!o.open) {
    if ((c.line.back().p - c.line.front().p).norm() > 0.1) return std::nullopt;
    c.line.pop_back();  // the start again
  }
  return c;
}

// Lap length, straights and the separation of the loop's parts (the rules and docs/track-generator.md).
bool acceptable(const Candidate& c, const TrackGeneratorOptions& o, const Layout& lay) {
  const auto& line = c.line;
  const std::size_t n = line.size();
  const bool closed = !o.open;
  const double total = closed ? line.back().s + (line.front().p - line.back().p).norm() : line.back().s;
  const double lap = closed ? total : c.end_s - c.start_s;
  if (lap < o.lap_min + kLapMargin || lap > o.lap_max - kLapMargin) return false;
  // Straights: runs of samples straighter than kStraightCurvature (round the seam on a loop).
  {
    std::size_t first_bent = n;
    for (std::size_t i = 0; i < n && first_bent == n; ++i)
      if (std::fabs(line[i].kappa) >= kStraightCurvature) first_bent = i;
    if (first_bent == n) return false;
    double run = 0;
    for (std::size_t k = 1; k <= (closed ? n : n - 1); ++k) {
      const std::size_t i = closed ? (first_bent + k) % n : k;
      const std::size_t prev = closed ? (i + n - 1) % n : i - 1;
      if (std::fabs(line[i].kappa) < kStraightCurvature)
        run += (line[i].p - line[prev].p).norm();
      else
        run = 0;
      // The open course's run-off is no straight of the track.
      if (run > kStraightMax && (closed || line[i].s <= c.end_s)) return false;
    }
  }
  // Two parts of the track are "different" where the way along the track between two points is over π/2 times
  // their distance (it turns through more than a half circle): there the centre lines keep a width plus the
  // separation apart, so their boundaries stay `separation` apart. A hairpin at the tightest radius meets this
  // with equality at the ends of its half circle.
  std::vector<std::size_t> sub;
  for (std::size_t i = 0; i < n; i += 10) sub.push_back(i);
  const double need = lay.width + o.separation - 0.02;
  for (std::size_t a = 0; a < sub.size(); ++a)
    for (std::size_t b = a + 1; b < sub.size(); ++b) {
      const CentreSample& p = line[sub[a]];
      const CentreSample& q = line[sub[b]];
      const double d = (p.p - q.p).norm();
      if (d >= need) continue;
      double along = std::fabs(q.s - p.s);
      if (closed) along = std::min(along, total - along);
      if (along > 0.5 * kPi * d + 0.3) return false;
    }
  return true;
}

}  // namespace

Track generate_loop(const TrackGeneratorOptions& o) {
  Rng rng(hash64(o.seed, 0x100 + static_cast<std::uint64_t>(o.kind), o.open ? 1 : 0));
  Layout lay;
  lay.width = sample_range(rng, o.width_min, o.width_max, 0.4, o.width_min);
  lay.spacing = sample_range(rng, o.spacing_min, o.spacing_max, 0.5, o.spacing_max);
  lay.yaw0 = rng.uniform(-kPi, kPi);
  lay.rc_min = std::max(kHairpinOuterMin - 0.5 * lay.width, 0.5 * (lay.width + o.separation));
  for (int attempt = 0; attempt < o.max_attempts; ++attempt) {
    const std::uint64_t attempt_seed = hash64(rng.next(), static_cast<std::uint64_t>(attempt));
    Rng draw_rng(attempt_seed);
    const auto c = draw(o, lay, draw_rng);
    if (!c || !acceptable(*c, o, lay)) continue;
    if (o.shares.hairpin_chain > 0.0 && c->chains == 0) continue;  // asked for chains: at least one
    // Hand placement draws from a stream of its own: the same centre line with or without it.
    Rng hand(hash64(attempt_seed, 0x4A17));
    if (auto t = loop_cones(*c, o, lay, hand)) return *t;
  }
  throw std::runtime_error("track generator: no " + std::string(to_string(o.kind)) + " layout for seed " +
                           std::to_string(o.seed) + " met every constraint in " + std::to_string(o.max_attempts) +
                           " attempts (loosen the options)");
}

}  // namespace fsd::sim::detail
