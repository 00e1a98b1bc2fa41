// The cones of a trackdrive/autocross loop: each boundary is the centre line offset by half the width, its cones
// spread along it (denser in turns), then the timing lines. On top, the hand placement of public layouts
// (docs/track-generator.md): uneven gaps, cones off their places, an inner cone out of its ring in tight turns,
// a narrowing. Each bends only the rule it names; the lane stays 3 m between cones elsewhere and the outside
// of a turn no tighter than the rules' 9 m.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>

#include "drivers/sim/track_generator/track_generator_detail.hpp"

namespace fsd::sim::detail {

namespace {

constexpr double kTimingOutside = 0.5;                  // m outside the boundary line (as the EPFL files place them)
constexpr double kMinConeGap = 1.0;                     // m: the densest spacing in tight turns
constexpr double kRamp = 3.0;                           // m of each smooth ramp into and out of a narrowing
constexpr double kPlateauMin = 3.0, kPlateauMax = 8.0;  // m of a narrowing at its narrowest
constexpr double kNarrowingGap = 1.5;                   // m: a narrowing's cones stand closer (it is to be seen)
constexpr double kTimingClear = 4.0;                    // m from a narrowing to a timing line or car_start
constexpr double kAnchorClear = 2.0;                    // m from a narrowing to a slalom cone
constexpr double kTightInner = 5.0;  // m: a turn whose inner boundary radius is under this gets an outlier,
constexpr double kTightTurn = std::numbers::pi / 2;  // when it turns through at least this
constexpr int kRingGaps = 6;      // a ring with an outlier is laid out in 6 gaps or more, so it can be measured
constexpr int kRingEachSide = 3;  // ring cones either side of the outlier, at least, so its ring is measurable

// The stretch where the lane narrows (sample indices): a ramp, the plateau, a ramp.
struct Narrowing {
  std::size_t first = 0, plateau_first = 0, plateau_last = 0, last = 0;
  double pinch = 0;  // m each boundary moves in on the plateau
  bool covers(std::size_t i) const { return pinch > 0.0 && i >= first && i <= last; }
};

// How far each boundary moves in at sample i: half a cosine up each ramp, `pinch` between them.
double pinch_at(const Narrowing& nw, const std::vector<CentreSample>& line, std::size_t i) {
  if (!nw.covers(i)) return 0.0;
  auto ramp = [](double t) { return 0.5 * (1.0 - std::cos(std::numbers::pi * std::clamp(t, 0.0, 1.0))); };
  if (i < nw.plateau_first)
    return nw.pinch * ramp((line[i].s - line[nw.first].s) / (line[nw.plateau_first].s - line[nw.first].s));
  if (i > nw.plateau_last)
    return nw.pinch * ramp((line[nw.last].s - line[i].s) / (line[nw.last].s - line[nw.plateau_last].s));
  return nw.pinch;
}

// The first sample at or past arc length s.
std::size_t index_at(const std::vector<CentreSample>& line, double s) {
  const auto it =
      std::lower_bound(line.begin(), line.end(), s, [](const CentreSample& a, double v) { return a.s < v; });
  return static_cast<std::size_t>(it - line.begin());
}

// A straight stretch of the first n samples for the narrowing, clear of car_start, the timing lines and the
// slalom's cones, drawn uniformly among those the line has; nothing when it has none.
std::optional<Narrowing> place_narrowing(const LoopCandidate& c, bool closed, std::size_t n, double pinch, Rng& hand) {
  const auto& line = c.line;
  const double plateau = hand.uniform(kPlateauMin, kPlateauMax), length = plateau + 2.0 * kRamp;
  const double total = closed ? line[n - 1].s + (line.front().p - line[n - 1].p).norm() : line[n - 1].s;
  std::vector<std::pair<double, double>> keep_out = {
      {c.start_s - kTimingClear, c.start_s + kStartLine + kTimingHalfGap + kTimingClear}};
  if (closed)
    keep_out.push_back({total - kTimingClear, total});  // behind car_start, round the seam
  else
    keep_out.push_back({c.end_s - 2.0 * kTimingHalfGap - kTimingClear, total});  // the finish line
  for (const auto& anchor : c.anchors)
    keep_out.push_back({line[anchor.first].s - kAnchorClear, line[anchor.first].s + kAnchorClear});
  std::vector<int> blocked_before(n + 1, 0);  // blocked samples before each index
  for (std::size_t i = 0; i < n; ++i) {
    bool blocked = std::fabs(line[i].kappa) >= kStraightCurvature;
    for (const auto& [a, b] : keep_out) blocked = blocked || (line[i].s >= a && line[i].s <= b);
    blocked_before[i + 1] = blocked_before[i] + (blocked ? 1 : 0);
  }
  std::vector<std::size_t> starts;
  for (std::size_t j = 0; j < n; ++j) {
    const std::size_t end = index_at(line, line[j].s + length);
    if (end >= n) break;
    if (blocked_before[end + 1] == blocked_before[j]) starts.push_back(j);
  }
  if (starts.empty()) return std::nullopt;
  const std::size_t pick = std::min(starts.size() - 1, static_cast<std::size_t>(hand.uniform() * starts.size()));
  const double s0 = line[starts[pick]].s;
  return Narrowing{starts[pick], index_at(line, s0 + kRamp), index_at(line, s0 + kRamp + plateau),
                   index_at(line, s0 + length), pinch};
}

// A stretch turning at one constant curvature (an arc) through kTightTurn or more whose inner boundary radius
// is under kTightInner: the boundaries from sample `first` to `last` lie on its rings.
struct Ring {
  std::size_t first = 0, last = 0;
  int inner = 1;  // the inner boundary: +1 left (a left turn), -1 right
  Vec2 centre = Vec2::Zero();
  double inner_length = 0;  // m of the inner ring
};

std::vector<Ring> tight_rings(const std::vector<CentreSample>& line, std::size_t n, double half) {
  std::vector<Ring> rings;
  std::size_t i = 1;
  while (i < n) {
    const double k = line[i].kappa;
    std::size_t j = i;
    while (j + 1 < n && line[j + 1].kappa == k) ++j;  // an arc's samples carry the very same curvature
    const double turned = std::fabs(line[j].heading - line[i - 1].heading);  // the arc starts at the sample before
    if (k != 0.0 && 1.0 / std::fabs(k) - half < kTightInner && turned >= kTightTurn) {
      const CentreSample& a = line[i];
      const Vec2 normal(-std::sin(a.heading), std::cos(a.heading));
      rings.push_back({i - 1, j, k > 0 ? 1 : -1, a.p + normal / k, turned * (1.0 / std::fabs(k) - half)});
    }
    i = j + 1;
  }
  return rings;
}

// One boundary's cones as placed, and which stay exactly where they are (slalom cones, a narrowing's, the rings
// that carry an outlier).
struct Side {
  int sign = 1;  // +1 left, -1 right
  std::vector<Vec2> line;
  std::vector<PlacedCone> cones;
  std::vector<bool> exact;
};

// In each tight ring with enough cones, one inner cone (not within two of the ring's ends) moved out of its
// ring into the lane. Returns how many.
int place_outliers(const std::vector<Ring>& rings, double amount, Side& left, Side& right, Rng& hand) {
  int placed = 0;
  for (const Ring& r : rings) {
    Side& side = r.inner > 0 ? left : right;
    std::vector<std::size_t> on_ring;
    for (std::size_t k = 0; k < side.cones.size(); ++k)
      if (side.cones[k].index >= r.first && side.cones[k].index <= r.last) on_ring.push_back(k);  // ends anchored
    if (on_ring.size() < 2 * kRingEachSide + 1) continue;
    const int span = static_cast<int>(on_ring.size()) - 2 * kRingEachSide;
    const std::size_t k = on_ring[static_cast<std::size_t>(kRingEachSide + hand.uniform_int(0, span - 1))];
    for (std::size_t m : on_ring) side.exact[m] = true;
    Vec2& p = side.cones[k].p;
    p += amount * (p - r.centre).normalized();  // away from the centre: into the lane
    ++placed;
  }
  return placed;
}

// How far each boundary point may move in towards the lane: the lane keeps 3 m between its boundaries, and the
// outside of a turn (within reach of the jitter) no tighter than the rules' 4.5 m radius.
std::vector<double> inward_room(const std::vector<CentreSample>& line, std::size_t n, int sign,
                                const std::vector<double>& half, double jitter) {
  const std::size_t reach = static_cast<std::size_t>(std::ceil(jitter / 0.05)) + 1;  // samples within the jitter
  std::vector<double> turn_room(n, 1e9);
  for (std::size_t i = 0; i < n; ++i) {
    const double k = line[i].kappa;
    if (sign * k >= 0.0) continue;  // this boundary is not the outside of a turn here
    const double room = 1.0 / std::fabs(k) + half[i] - kHairpinOuterMin;
    for (std::size_t d = 0; d <= 2 * reach; ++d) {
      const std::size_t j = (i + n + d - reach) % n;
      turn_room[j] = std::min(turn_room[j], room);
    }
  }
  std::vector<double> room(n);
  for (std::size_t i = 0; i < n; ++i) room[i] = std::max(0.0, std::min(half[i] - 0.5 * kLaneMin, turn_room[i]));
  return room;
}

// Each cone not kept exact moved by up to `jitter` in a disc, never further in than the room there.
void jitter_cones(Side& side, const std::vector<double>& room, double jitter, Rng& hand) {
  const std::size_t n = side.line.size();
  for (std::size_t k = 0; k < side.cones.size(); ++k) {
    if (side.exact[k]) continue;
    const std::size_t i = std::min(side.cones[k].index, n - 2);
    const Vec2 along = (side.line[i + 1] - side.line[i]).normalized();
    const Vec2 outward = side.sign * Vec2(-along.y(), along.x());
    const Vec2 d = hand_offset(hand, jitter, std::min(room[i], room[i + 1]));
    side.cones[k].p += d.x() * along + d.y() * outward;
  }
}

}  // namespace

std::optional<Track> loop_cones(const LoopCandidate& c, const TrackGeneratorOptions& o, const LoopLayout& lay,
                                Rng& hand) {
  const bool closed = !o.open;
  const double half = 0.5 * lay.width;
  std::size_t n = c.line.size();
  if (!closed)
    while (n > 1 && c.line[n - 1].s > c.end_s + 1e-9) --n;  // no cones on the run-off
  Narrowing nw;
  if (o.narrowing > 0.0) {
    const auto placed = place_narrowing(c, closed, n, 0.5 * (lay.width - o.narrowing), hand);
    if (!placed) return std::nullopt;
    nw = *placed;
  }
  // Room for the jitter within the rules' gaps, and for uneven gaps within what is asked.
  const double cap = lay.spacing - 2.0 * o.cone_jitter, uneven = 1.0 + o.spacing_jitter;
  auto spacing = [&](double kappa) {
    return std::fabs(kappa) < 1e-9 ? cap : std::clamp(o.turn_angle / std::fabs(kappa), kMinConeGap, cap);
  };
  Side left{1, std::vector<Vec2>(n), {}, {}}, right{-1, std::vector<Vec2>(n), {}, {}};
  std::vector<double> sp_left(n), sp_right(n), half_at(n);
  for (std::size_t i = 0; i < n; ++i) {
    const CentreSample& s = c.line[i];
    const Vec2 normal(-std::sin(s.heading), std::cos(s.heading));
    const double h = half - pinch_at(nw, c.line, i);
    half_at[i] = h;
    left.line[i] = s.p + h * normal;
    right.line[i] = s.p - h * normal;
    // Each boundary is an offset curve: its curvature is κ / (1 ∓ κ·h).
    // Uneven gaps spread about a shorter even one, but not below the 1 m floor: gaps may shrink by a share and
    // cones move by the jitter without swapping places.
    sp_left[i] = std::max(kMinConeGap, spacing(s.kappa / (1.0 - s.kappa * h)) / uneven);
    sp_right[i] = std::max(kMinConeGap, spacing(s.kappa / (1.0 + s.kappa * h)) / uneven);
    if (nw.covers(i)) sp_left[i] = sp_right[i] = std::min(sp_left[i], kNarrowingGap / uneven);
  }
  std::vector<std::size_t> anchor_left, anchor_right;
  for (const auto& [i, side] : c.anchors)
    if (i < n) (side > 0 ? anchor_left : anchor_right).push_back(i);
  if (nw.pinch > 0.0)  // the plateau's ends carry a cone on each side
    for (auto* a : {&anchor_left, &anchor_right}) a->insert(a->end(), {nw.plateau_first, nw.plateau_last});
  // A tight turn's inner ring laid out by hand from end to end in kRingGaps gaps or more, so that it has its
  // cones to stand out of.
  const std::vector<Ring> rings = o.inner_outlier > 0.0 ? tight_rings(c.line, n, half) : std::vector<Ring>{};
  for (const Ring& r : rings) {
    auto& anchors = r.inner > 0 ? anchor_left : anchor_right;
    anchors.insert(anchors.end(), {r.first, r.last});
    auto& sp = r.inner > 0 ? sp_left : sp_right;
    for (std::size_t i = r.first; i <= r.last; ++i) sp[i] = std::min(sp[i], r.inner_length / kRingGaps / uneven);
  }
  for (auto* a : {&anchor_left, &anchor_right}) {
    std::sort(a->begin(), a->end());
    a->erase(std::unique(a->begin(), a->end()), a->end());
  }
  auto place = [&](Side& side, const std::vector<double>& sp, const std::vector<std::size_t>& anchors) {
    side.cones = place_cones_along(side.line, sp, closed, anchors, o.spacing_jitter, &hand);
    side.exact.assign(side.cones.size(), false);
    for (std::size_t k = 0; k < side.cones.size(); ++k) {
      const std::size_t i = side.cones[k].index;
      side.exact[k] = nw.covers(i) || std::binary_search(anchors.begin(), anchors.end(), i);
    }
  };
  place(left, sp_left, anchor_left);
  place(right, sp_right, anchor_right);
  if (o.inner_outlier > 0.0 && place_outliers(rings, o.inner_outlier, left, right, hand) == 0) return std::nullopt;
  if (o.cone_jitter > 0.0)
    for (Side* side : {&left, &right})
      jitter_cones(*side, inward_room(c.line, n, side->sign, half_at, o.cone_jitter), o.cone_jitter, hand);
  Track t;
  t.start = {0.0, 0.0, lay.yaw0};
  for (const PlacedCone& p : left.cones) add_cone(t, ConeRole::Left, p.p);
  for (const PlacedCone& p : right.cones) add_cone(t, ConeRole::Right, p.p);
  // Timing lines: two big orange cones each side, just outside the boundary lines.
  auto timing_line = [&](double s_line) {
    for (double ds : {-kTimingHalfGap, kTimingHalfGap}) {
      const double q = s_line + ds;
      const auto it =
          std::lower_bound(c.line.begin(), c.line.end(), q, [](const CentreSample& a, double v) { return a.s < v; });
      const CentreSample& s = it == c.line.end() ? c.line.back() : *it;
      const Vec2 normal(-std::sin(s.heading), std::cos(s.heading));
      const Vec2 p = s.p + (q - s.s) * Vec2(std::cos(s.heading), std::sin(s.heading));
      add_cone(t, ConeRole::Timing, p + (half + kTimingOutside) * normal);
      add_cone(t, ConeRole::Timing, p - (half + kTimingOutside) * normal);
    }
  };
  timing_line(c.start_s + kStartLine);
  if (!closed) timing_line(c.end_s - kTimingHalfGap);
  return t;
}

}  // namespace fsd::sim::detail
