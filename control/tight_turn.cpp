#include "control/tight_turn.hpp"

#include "control/smoothing.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

namespace fsd {
namespace {

constexpr double kPi = std::numbers::pi;

struct Segment {
  std::size_t first = 0, last = 0;  // point indices, inclusive
  double turn = 0;                  // signed heading change, rad
  std::optional<TightTurn> held;    // the turn when known already (a held turn)
  bool refit = true;                // a held turn's rings fitted again from the cones beside it
};

// The stretch from the car that lies within a held turn's outer ring (with a metre to spare), turning its way,
// up to where the path curves the other way (an S: the next hairpin's entry lies within this one's ring, and a
// rejoin beyond it would cut straight through the next hairpin's inner cones). Beside the car the midline may bend
// either way past the middle of a hairpin, so only bends `lead` or more ahead end the stretch.
std::optional<Segment> held_segment(const Path& path, const TightTurn& held, const TightTurnConfig& cfg) {
  const auto& pts = path.points;
  const double reach = held.outer_radius + 1.0;
  if ((pts.front().p - held.centre).norm() > reach) return std::nullopt;
  // Past the end of its turn-out the car has left the turn: the next turn is found as any other. Past along the
  // exit's direction and, round the turn's centre, just beyond the exit (within a quarter turn): a hairpin's exit
  // straight runs back beside its entry, where a car still coming in stands "past" the exit along that direction.
  const Vec2 a = pts.front().p - held.centre, b = held.exit - held.centre;
  const double to_exit = held.direction * signed_angle(a, b);  // still to turn
  const bool beyond_exit_line = (held.exit - pts.front().p).dot(held.exit_direction) <= 0;
  if (beyond_exit_line && to_exit <= 0 && to_exit > -kPi / 2) return std::nullopt;
  Segment seg;
  seg.held = held;
  // Still coming in beside the exit straight: the rings fitted further out, with the whole turn in view, hold.
  seg.refit = !beyond_exit_line;
  while (seg.last + 1 < pts.size() && (pts[seg.last + 1].p - held.centre).norm() <= reach) {
    const auto& next = pts[seg.last + 1];
    if (next.s - pts.front().s >= cfg.lead && next.kappa * held.direction < -cfg.kappa_on) break;
    seg.turn += 0.5 * (pts[seg.last + 1].kappa + pts[seg.last].kappa) * (pts[seg.last + 1].s - pts[seg.last].s);
    ++seg.last;
  }
  if (seg.last == 0) return std::nullopt;
  // The way round is the held turn's, whatever the midline does beside the car (it may bend the other way).
  if (seg.turn * held.direction <= 0) seg.turn = 1e-3 * held.direction;
  return seg;
}

// The first stretch from point `from` on curving tighter than kappa_on one way that turns at least min_turn (or
// starts at the path's first point: the car).
std::optional<Segment> find_turn(const Path& path, const TightTurnConfig& cfg, std::size_t from) {
  const auto& pts = path.points;
  std::size_t i = from;
  while (i < pts.size()) {
    if (std::abs(pts[i].kappa) <= cfg.kappa_on) {
      ++i;
      continue;
    }
    Segment seg;
    seg.first = i;
    const double sign = pts[i].kappa > 0 ? 1.0 : -1.0;
    while (i < pts.size() && pts[i].kappa * sign > cfg.kappa_on) {
      if (i > seg.first) seg.turn += 0.5 * (pts[i].kappa + pts[i - 1].kappa) * (pts[i].s - pts[i - 1].s);
      seg.last = i++;
    }
    const bool at_car = seg.first == 0;
    if (std::abs(seg.turn) >= cfg.min_turn_deg * kPi / 180.0 || (at_car && seg.last > seg.first)) return seg;
  }
  return std::nullopt;
}

// Least-squares fit of two concentric circles: inner cones on one, outer cones on the other (Gauss–Newton).
bool fit_rings(const std::vector<Vec2>& inner, const std::vector<Vec2>& outer, TightTurn& t) {
  auto mean_distance = [&](const std::vector<Vec2>& q) {
    double sum = 0;
    for (const auto& p : q) sum += (p - t.centre).norm();
    return sum / static_cast<double>(q.size());
  };
  t.inner_radius = mean_distance(inner);
  t.outer_radius = mean_distance(outer);
  for (int iter = 0; iter < 10; ++iter) {
    Eigen::Matrix4d jtj = Eigen::Matrix4d::Zero();
    Eigen::Vector4d jte = Eigen::Vector4d::Zero();
    auto add = [&](const std::vector<Vec2>& q, int ring) {
      for (const auto& p : q) {
        const Vec2 d = p - t.centre;
        const double n = d.norm();
        if (n < 1e-6) continue;
        Eigen::Vector4d j(-d.x() / n, -d.y() / n, ring == 0 ? -1.0 : 0.0, ring == 1 ? -1.0 : 0.0);
        const double e = n - (ring == 0 ? t.inner_radius : t.outer_radius);
        jtj += j * j.transpose();
        jte += j * e;
      }
    };
    add(inner, 0);
    add(outer, 1);
    const Eigen::Vector4d step = jtj.ldlt().solve(-jte);
    if (!step.allFinite()) return false;
    t.centre += step.head<2>();
    t.inner_radius += step(2);
    t.outer_radius += step(3);
    if (step.norm() < 1e-6) break;
  }
  double sq = 0;
  for (const auto& p : inner) sq += std::pow((p - t.centre).norm() - t.inner_radius, 2);
  for (const auto& p : outer) sq += std::pow((p - t.centre).norm() - t.outer_radius, 2);
  const double rms = std::sqrt(sq / static_cast<double>(inner.size() + outer.size()));
  return rms < 0.3 && t.inner_radius > 0.3 && t.outer_radius - t.inner_radius > 2.0 &&
         t.outer_radius - t.inner_radius < 8.0;
}

// Where the tangent from `p` touches the circle, for travel round it in direction `dir` (+1 counter-clockwise):
// arriving from p when `arriving`, else leaving towards p.
std::optional<Vec2> tangent_point(const Vec2& c, double r, const Vec2& p, double dir, bool arriving) {
  const Vec2 d = p - c;
  const double dist = d.norm();
  if (dist <= r + 1e-6) return std::nullopt;
  const double a = std::acos(r / dist);
  for (double sgn : {1.0, -1.0}) {
    const Vec2 u = d / dist;
    const double ca = std::cos(sgn * a), sa = std::sin(sgn * a);
    const Vec2 t = c + r * Vec2(ca * u.x() - sa * u.y(), sa * u.x() + ca * u.y());
    const Vec2 radial = t - c;
    const Vec2 velocity = dir * Vec2(-radial.y(), radial.x());
    const Vec2 chord = arriving ? Vec2(t - p) : Vec2(p - t);
    if (chord.dot(velocity) > 0) return t;
  }
  return std::nullopt;
}

// A stretch of curve whose curvature changes linearly from k0 to k1 (unsigned) over `length`.
struct Piece {
  double length, k0, k1;
};

struct Curve {
  std::vector<Vec2> points;  // from the start, about ds apart
  Vec2 end = Vec2::Zero();
  double heading = 0;
  // Centre of the circle of radius r tangent at the end (to the left: the curve turns left when dir > 0).
  Vec2 centre_of(double r, double dir = 1.0) const {
    return end + dir * r * Vec2(-std::sin(heading), std::cos(heading));
  }
};

// Integrates the pieces from `start` at `heading`, turning left (dir > 0) or right, by the midpoint rule.
Curve integrate(const Vec2& start, double heading, const std::vector<Piece>& pieces, double ds, double dir = 1.0) {
  Curve c;
  c.end = start;
  c.heading = heading;
  c.points.push_back(start);
  const double h = ds / 8;
  for (const auto& p : pieces) {
    const int n = std::max(1, static_cast<int>(std::ceil(p.length / h)));
    const double step = p.length / n;
    double since = 0;
    for (int k = 0; k < n; ++k) {
      const double k_mid = p.k0 + (p.k1 - p.k0) * (k + 0.5) / n;
      const double mid_heading = c.heading + 0.5 * dir * k_mid * step;
      c.end += step * Vec2(std::cos(mid_heading), std::sin(mid_heading));
      c.heading += dir * k_mid * step;
      since += step;
      if (since >= ds - 1e-9) {
        c.points.push_back(c.end);
        since = 0;
      }
    }
  }
  if ((c.points.back() - c.end).norm() > 1e-9) c.points.push_back(c.end);
  return c;
}

void append_line(std::vector<Vec2>& out, const Vec2& a, const Vec2& b, double ds) {
  const int n = std::max(1, static_cast<int>(std::ceil((b - a).norm() / ds)));
  for (int k = 1; k <= n; ++k) out.push_back(a + (b - a) * (static_cast<double>(k) / n));
}

// Rebuilds `path` through the turn `seg` when the cones confirm a tight turn there, leaving the path `lead_in`
// before the stretch and rejoining it `lead_out` after.
std::optional<TightTurn> shape_segment(Path& path, const std::optional<Segment>& seg, const std::vector<Vec2>& cones,
                                       const TightTurnConfig& cfg, double lead_in, double lead_out) {
  if (!seg) return std::nullopt;
  const auto& pts = path.points;
  const double dir = seg->turn > 0 ? 1.0 : -1.0;
  const double ds = std::max(0.05, path.length() / static_cast<double>(pts.size() - 1));

  // First guess of the centre: the held turn's, else the mean centre of curvature of the stretch.
  TightTurn turn;
  if (seg->held) {
    turn.centre = seg->held->centre;
  } else {
    for (std::size_t i = seg->first; i <= seg->last; ++i) {
      const Vec2 normal(-std::sin(pts[i].yaw), std::cos(pts[i].yaw));
      turn.centre += pts[i].p + normal / pts[i].kappa;
    }
    turn.centre /= static_cast<double>(seg->last - seg->first + 1);
  }
  turn.direction = static_cast<int>(dir);

  // Cones beside the stretch, inside or outside the path as seen from that centre.
  std::vector<Vec2> inner, outer;
  const double s_first = pts[seg->first].s - 2.0, s_last = pts[seg->last].s + 2.0;
  for (const auto& c : cones) {
    if ((c - turn.centre).norm() > 2.0 * cfg.lane_radius_max + 2.0) continue;
    const auto foot = project(path, c);
    if (!foot || foot->s < s_first || foot->s > s_last || foot->distance() > 4.0) continue;
    ((c - turn.centre).norm() < (foot->foot - turn.centre).norm() ? inner : outer).push_back(c);
  }
  const bool fitted = seg->refit && inner.size() >= 2 && outer.size() >= 2 && inner.size() + outer.size() >= 5 &&
                      fit_rings(inner, outer, turn);
  if (fitted) {
    turn.outer_nearest = turn.outer_radius;
    for (const auto& p : outer) turn.outer_nearest = std::min(turn.outer_nearest, (p - turn.centre).norm());
    // The inner side's limit is the farthest inner cone round the stretch's arc (a ring of cones is no perfect
    // circle; its mean radius would let the body brush the cones that stand out), not one beside the straights.
    turn.inner_farthest = turn.inner_radius;
    const Vec2 from = pts[seg->first].p - turn.centre;
    const double span = std::abs(seg->turn);
    for (const auto& p : inner) {
      const Vec2 d = p - turn.centre;
      double round = dir * signed_angle(from, d);
      if (round < 0) round += 2 * kPi;
      if (round <= span) turn.inner_farthest = std::max(turn.inner_farthest, d.norm());
    }
  } else if (seg->held) {
    // Past the middle of the turn the cones still ahead are too few to fit, or lie on the exit straight: the
    // rings fitted on the way in hold (they are fixed in the map; the pose carries them into this frame).
    turn = *seg->held;
  } else {
    return std::nullopt;
  }
  if (0.5 * (turn.inner_radius + turn.outer_radius) > cfg.lane_radius_max) return std::nullopt;

  // The rear axle's radius: at least the lock's (with a margin), at most what keeps the nose off the outer cones,
  // in the middle of what the cones leave where that fits.
  const double keep = cfg.cone_radius + cfg.clearance;
  const double r_kinematic = cfg.wheelbase / std::tan(cfg.max_steer);  // the rear axle's at the lock
  const double r_lock = r_kinematic * (1.0 + cfg.lock_margin);
  const double r_in = turn.inner_farthest + keep + cfg.body_half_width;
  const double out = turn.outer_nearest - keep;
  const double r_out =
      out > cfg.body_front ? std::sqrt(out * out - cfg.body_front * cfg.body_front) - cfg.body_half_width : 0.0;
  // The lane's middle where it is wider than the lock's radius; where it is not (the rules' tightest hairpin), the
  // line keeps off the lock by lock_authority if the nose leaves room, else by half of what it leaves: on an arc at
  // the lock the follower has no steering left, and an entry a few centimetres off becomes an eccentric circle
  // that carries the nose out by twice as much.
  const double r_authority = r_kinematic * (1.0 + cfg.lock_authority);
  const double wanted = std::max(0.5 * (r_in + r_out), std::min(r_authority, 0.5 * (r_lock + r_out)));
  turn.radius = std::max(r_lock, std::min(wanted, r_out));
  turn.room = std::max(0.0, std::min(r_out - turn.radius, turn.radius - r_in));

  // The car cannot step its steering onto the arc: it turns in along a clothoid (curvature rising linearly over
  // transition_length), and a clothoid–arc–clothoid keeps its arc concentric with the turn only if its straights
  // run a little wider, at `line_radius` from the centre, and it turns in half a transition before the tangent
  // point. Both follow from integrating the clothoid once.
  const Vec2& c = turn.centre;
  const double r = turn.radius;
  const double kappa = 1.0 / r;
  const double L = std::max(ds, cfg.transition_length);
  const Vec2 clothoid_centre = integrate(Vec2::Zero(), 0.0, {{L, 0.0, kappa}}, ds / 4).centre_of(r);
  const double line_radius = clothoid_centre.y(), turn_in = clothoid_centre.x();

  const double s_in = std::max(pts[seg->first].s - lead_in, pts.front().s);
  const double s_out = pts[seg->last].s + lead_out;
  const Vec2 p_in = sample(path, s_in).p;
  std::vector<Vec2> out_pts;
  for (const auto& q : pts) {
    if (q.s >= s_in) break;
    out_pts.push_back(q.p);
  }
  // Exit: the straight from the tangent point on the wider circle out to the path `lead` after the stretch, or to
  // the path's end.
  const bool rejoin = s_out < pts.back().s - 0.5;
  const Vec2 p_out = rejoin ? sample(path, s_out).p : pts.back().p;
  const auto exit_foot = tangent_point(c, line_radius, p_out, dir, false);
  if (!exit_foot) return std::nullopt;
  const Vec2 u_out = (p_out - *exit_foot).normalized();

  Vec2 start;
  double heading;
  std::vector<Piece> pieces;
  const auto entry_foot = tangent_point(c, line_radius, p_in, dir, true);
  const Vec2 u_in = entry_foot ? Vec2((*entry_foot - p_in).normalized()) : Vec2::Zero();
  if (entry_foot && (*entry_foot - p_in).dot(u_in) > turn_in) {
    // Straight from p_in to the turn-in point, then the clothoid up.
    start = *entry_foot - turn_in * u_in;
    out_pts.push_back(p_in);
    append_line(out_pts, p_in, start, ds);
    heading = std::atan2(u_in.y(), u_in.x());
    pieces.push_back({L, 0.0, kappa});
  } else {
    // The car is in the turn already (or too near its start to turn in): the arc starts beside the path's start.
    const Vec2 radial = (p_in - c).normalized();
    start = c + r * radial;
    out_pts.push_back(start);
    heading = std::atan2(dir * radial.x(), -dir * radial.y());
  }
  // Heading change left for the arc: up to the exit straight's direction, less the exit clothoid's.
  double total = dir * (std::atan2(u_out.y(), u_out.x()) - heading);
  while (total < 0) total += 2 * kPi;
  while (total >= 2 * kPi) total -= 2 * kPi;
  const double arc = total - kappa * L * (pieces.empty() ? 0.5 : 1.0);
  // The turn must go the way the stretch does and by about as much: anything else is a misfit.
  if (arc < 0 || total > 1.8 * kPi || total < 0.5 * std::abs(seg->turn) - 0.5) return std::nullopt;
  turn.sweep = total;
  pieces.push_back({arc * r, kappa, kappa});
  pieces.push_back({L, kappa, 0.0});
  // Dense points (a quarter of ds) so that resampling along chords adds no curvature ripple on a 3 m arc.
  Curve curve = integrate(start, heading, pieces, ds / 4, dir);
  turn.exit = curve.end;
  turn.exit_direction = u_out;
  out_pts.insert(out_pts.end(), curve.points.begin() + 1, curve.points.end());
  if (rejoin) {
    // The arc and its turn-out must end before the point they rejoin, or the rest of the path would be lost.
    if ((p_out - curve.end).dot(u_out) <= 0) return std::nullopt;
    append_line(out_pts, curve.end, p_out, ds);
    for (const auto& q : pts)
      if (q.s > s_out) out_pts.push_back(q.p);
  }

  Path shaped;
  shaped.stamp = path.stamp;
  for (const auto& p : out_pts)
    if (shaped.points.empty() || (p - shaped.points.back().p).norm() > 1e-3) shaped.points.push_back({p, 0, 0, 0, 0});
  if (shaped.points.size() < 2) return std::nullopt;
  compute_geometry(shaped);
  // Round the joins (a kink where the straight leaves the path, the step in curvature at the tangent points); a
  // short wavelength leaves the arc itself where it is.
  path = smooth_path(shaped, ds, cfg.smoothing_wavelength);
  const auto back_on = project(path, p_out);
  turn.s_begin = s_in;
  turn.s_end = back_on ? back_on->s : path.length();
  return turn;
}

// The sharpest bend of the rebuilt stretch, with the rounding of its joins (a little either side of it).
double sharpest_bend(const Path& path, const TightTurn& turn) {
  constexpr double kJoin = 2.0;  // m, beyond the rounding's reach (TightTurnConfig::smoothing_wavelength)
  double k = 0;
  for (const auto& q : path.points)
    if (q.s >= turn.s_begin - kJoin && q.s <= turn.s_end + kJoin) k = std::max(k, std::abs(q.kappa));
  return k;
}

// Whether the rebuilt stretch keeps the body's half width and a cone's radius off every cone.
bool clear_of_cones(const Path& path, const TightTurn& turn, const std::vector<Vec2>& cones,
                    const TightTurnConfig& cfg) {
  const double keep = cfg.body_half_width + cfg.cone_radius;
  for (const auto& c : cones)
    for (const auto& q : path.points)
      if (q.s >= turn.s_begin && q.s <= turn.s_end && (q.p - c).squaredNorm() < keep * keep) return false;
  return true;
}

// shape_segment with the path left and rejoined `lead` before and after the turn. Where the path bends the other
// way just before or after the turn (an S into or out of a hairpin), the straight to it can meet it at an angle
// that the joins' rounding turns into a bend sharper than the lock: then shorter and longer leads (0.3–2 × lead)
// are tried, and the first whose joins stay within the lock and whose straights pass no cone is taken (else the
// one that bends least of those clear of the cones, else the plain one).
std::optional<TightTurn> shape_segment_within_lock(Path& path, const std::optional<Segment>& seg,
                                                   const std::vector<Vec2>& cones, const TightTurnConfig& cfg) {
  const double kappa_lock = std::tan(cfg.max_steer) / cfg.wheelbase;
  Path plain = path;
  const auto turn = shape_segment(plain, seg, cones, cfg, cfg.lead, cfg.lead);
  if (!turn) return std::nullopt;
  if (sharpest_bend(plain, *turn) <= kappa_lock) {
    path = std::move(plain);
    return turn;
  }
  std::optional<TightTurn> best;
  Path best_path;
  double best_bend = std::numeric_limits<double>::infinity();
  // One side changed first (the bend is usually on one side), then both.
  static const std::array<std::pair<double, double>, 12> kLeads = {{{1.0, 0.6},
                                                                    {1.0, 0.3},
                                                                    {1.0, 1.5},
                                                                    {1.0, 2.0},
                                                                    {0.6, 1.0},
                                                                    {0.3, 1.0},
                                                                    {1.5, 1.0},
                                                                    {2.0, 1.0},
                                                                    {0.6, 0.6},
                                                                    {1.5, 1.5},
                                                                    {0.6, 1.5},
                                                                    {1.5, 0.6}}};
  for (const auto& [in, out] : kLeads) {
    Path trial = path;
    const auto other = shape_segment(trial, seg, cones, cfg, in * cfg.lead, out * cfg.lead);
    if (!other || !clear_of_cones(trial, *other, cones, cfg)) continue;
    const double bend = sharpest_bend(trial, *other);
    if (bend <= kappa_lock) {
      path = std::move(trial);
      return other;
    }
    if (bend < best_bend) best_bend = bend, best = other, best_path = std::move(trial);
  }
  path = best ? std::move(best_path) : std::move(plain);
  return best ? best : turn;
}

}  // namespace

double room_speed(const TightTurn& turn, const TightTurnConfig& cfg) {
  if (cfg.understeer <= 0 || turn.radius <= 0) return cfg.v_max;
  const double v = std::sqrt(cfg.room_share * turn.room * cfg.wheelbase / (turn.radius * cfg.understeer));
  return std::clamp(v, std::min(cfg.v_min, cfg.v_max), cfg.v_max);
}

TightTurn transformed(TightTurn turn, const Pose2& by) {
  turn.centre = by.transform(turn.centre);
  turn.exit = by.transform(turn.exit);
  turn.exit_direction = by.rotation() * turn.exit_direction;
  return turn;
}

std::vector<TightTurn> shape_tight_turns(Path& path, const std::vector<Vec2>& cones, const TightTurnConfig& cfg,
                                         const TightTurn* held) {
  std::vector<TightTurn> turns;
  if (!cfg.enabled || path.closed || path.points.size() < 4) return turns;
  // The index of the first point past a shaped turn's turn-out: the next turn is looked for from there (not from
  // where the path is rejoined, which may lie in the next turn already).
  auto after = [&path](const TightTurn& turn) {
    const auto out = project(path, turn.exit);
    const double s_exit = out ? out->s : turn.s_end;
    std::size_t i = 0;
    while (i < path.points.size() && path.points[i].s <= s_exit) ++i;
    return i;
  };
  std::size_t from = 0;
  if (held && held->direction != 0)
    if (auto turn = shape_segment_within_lock(path, held_segment(path, *held, cfg), cones, cfg)) {
      turns.push_back(*turn);
      from = after(*turn);
    }
  while (const auto seg = find_turn(path, cfg, from)) {
    if (auto turn = shape_segment_within_lock(path, seg, cones, cfg)) {
      turns.push_back(*turn);
      from = after(*turn);
    } else {
      from = seg->last + 1;
    }
  }
  return turns;
}

std::vector<TightTurn> shape_tight_turns_on_lap(Path& lap, const std::vector<Vec2>& cones, const TightTurnConfig& cfg) {
  std::vector<TightTurn> turns;
  const std::size_t n = lap.points.size();
  if (!cfg.enabled || !lap.closed || n < 16) return turns;
  // Open the loop where it is straightest (least |κ| over ±5 m), so that no turn is cut in two.
  const double ds = lap.length() / static_cast<double>(n);
  const auto half = static_cast<std::size_t>(std::max(1.0, 5.0 / ds));
  std::size_t cut = 0;
  double least = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < n; ++i) {
    double sum = 0;
    for (std::size_t k = 0; k <= 2 * half; ++k) sum += std::abs(lap.points[(i + n + k - half) % n].kappa);
    if (sum < least) least = sum, cut = i;
  }
  Path open;
  open.stamp = lap.stamp;
  for (std::size_t k = 0; k <= n; ++k) open.points.push_back({lap.points[(cut + k) % n].p, 0, 0, 0, 0});
  compute_geometry(open);
  std::size_t from = 1;  // the first point is on the straight the loop was opened on: not "the car in a turn"
  while (const auto seg = find_turn(open, cfg, from)) {
    if (auto turn = shape_segment_within_lock(open, seg, cones, cfg)) {
      turns.push_back(*turn);
      from = 0;
      while (from < open.points.size() && open.points[from].s <= turn->s_end) ++from;
    } else {
      from = seg->last + 1;
    }
  }
  if (turns.empty()) return turns;
  // Close it again: the last point repeats the first.
  if (open.points.size() > 2 && (open.points.back().p - open.points.front().p).norm() < 0.5 * ds)
    open.points.pop_back();
  open.closed = true;
  compute_geometry(open);
  lap = std::move(open);
  return turns;
}

}  // namespace fsd
