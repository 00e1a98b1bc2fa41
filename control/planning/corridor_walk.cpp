#include "control/planning/corridor_walk.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <set>

#include "control/planning/triangulation.hpp"

namespace fsd {

namespace {

// One step of a walk: the car crossed `edge` into triangle `next_tri` (−1: left the triangulation).
struct Node {
  int edge = -1;
  int next_tri = -1;
  int parent = -1;
  Vec2 m = Vec2::Zero();       // edge midpoint
  Vec2 normal = Vec2::Zero();  // unit normal of the edge in the direction of travel
  double heading = 0;
  double cost = 0;
  double length = 0;
  double width_ref = 0;
  double colour_cost = 0;  // the part of cost that comes from colours (unknown or contradicting)
  int conflicts = 0;       // cones passed on the side their colour contradicts
  // The last two cones passed on each side (0 left, 1 right): the boundaries as the walk has seen them.
  std::array<int, 2> last{-1, -1}, prev{-1, -1};
};

// The chosen walk: its midpoints, and how much of its cost the colours decided.
struct Walk {
  std::vector<Vec2> mids;
  std::vector<std::pair<int, int>> passed;  // (cone, side it was passed on: +1 left, −1 right)
  int conflicts = 0;
  double geometric_score = 0;  // score without the colour terms
};

class Walker {
 public:
  Walker(const CorridorWalkConfig& c, const std::vector<WalkCone>& cones, const Triangulation& tri)
      : c_(c), cones_(cones), tri_(tri) {
    crossable_.resize(tri.edges.size());
    for (std::size_t i = 0; i < tri.edges.size(); ++i) {
      const auto& e = tri.edges[i];
      const WalkCone& a = cones_[static_cast<std::size_t>(e.a)];
      const WalkCone& b = cones_[static_cast<std::size_t>(e.b)];
      const double len = (a.p - b.p).norm();
      const bool left_right = a.side * b.side == -1;
      crossable_[i] = len >= c.width_min && len <= (left_right ? c.crossing_max : c.width_max);
    }
  }

  // Best walk from the car (origin, heading +x: the planner works in the vehicle frame), as midpoints.
  Walk walk() {
    seed();
    for (int depth = 0; depth < c_.max_depth && !beam_.empty(); ++depth) {
      std::map<std::pair<int, int>, int> best_of;  // (edge, next triangle) → candidate node
      std::vector<int> candidates;
      for (const int u : beam_) {
        const Node nu = nodes_[static_cast<std::size_t>(u)];
        if (nu.length >= c_.horizon || nu.next_tri < 0) {
          finals_.push_back(u);
          continue;
        }
        int expansions = 0;
        for (const int f : tri_.triangle_edges[static_cast<std::size_t>(nu.next_tri)]) {
          Node nn;
          if (f == nu.edge || !crossable_[static_cast<std::size_t>(f)] || !step(u, nu, f, nn)) continue;
          ++expansions;
          const int id = push(nn);
          const auto key = std::make_pair(f, nn.next_tri);
          const auto it = best_of.find(key);
          if (it == best_of.end()) {
            best_of.emplace(key, id);
            candidates.push_back(id);
          } else if (score(id) < score(it->second)) {
            std::replace(candidates.begin(), candidates.end(), it->second, id);
            it->second = id;
          }
        }
        if (expansions == 0) finals_.push_back(u);
      }
      std::sort(candidates.begin(), candidates.end(), [&](int a, int b) { return score(a) < score(b); });
      if (candidates.size() > static_cast<std::size_t>(c_.beam_width))
        candidates.resize(static_cast<std::size_t>(c_.beam_width));
      beam_ = std::move(candidates);
    }
    finals_.insert(finals_.end(), beam_.begin(), beam_.end());
    if (finals_.empty()) return {};
    const int best =
        *std::min_element(finals_.begin(), finals_.end(), [&](int a, int b) { return score(a) < score(b); });
    // Even the best walk may be implausible (the track ends, or only the next stretch of track is in view).
    if (score(best) > c_.max_score) return {};
    Walk out;
    const Node& b = nodes_[static_cast<std::size_t>(best)];
    out.conflicts = b.conflicts;
    out.geometric_score = score(best) - b.colour_cost;
    for (int u = best; u >= 0; u = nodes_[static_cast<std::size_t>(u)].parent) {
      const Node& q = nodes_[static_cast<std::size_t>(u)];
      out.mids.push_back(q.m);
      const auto& e = tri_.edges[static_cast<std::size_t>(q.edge)];
      for (const int v : {e.a, e.b}) out.passed.emplace_back(v, crossing_side(v, q.edge, q.normal));
    }
    std::reverse(out.mids.begin(), out.mids.end());
    return out;
  }

 private:
  const Vec2& cone(int i) const { return cones_[static_cast<std::size_t>(i)].p; }
  Vec2 midpoint(int e) const {
    const auto& ed = tri_.edges[static_cast<std::size_t>(e)];
    return 0.5 * (cone(ed.a) + cone(ed.b));
  }
  Vec2 edge_normal(int e) const {
    const auto& ed = tri_.edges[static_cast<std::size_t>(e)];
    const Vec2 t = (cone(ed.b) - cone(ed.a)).normalized();
    return {-t.y(), t.x()};
  }
  Vec2 third_vertex(int t, int e) const {
    const auto& ed = tri_.edges[static_cast<std::size_t>(e)];
    for (const int v : tri_.triangles[static_cast<std::size_t>(t)])
      if (v != ed.a && v != ed.b) return cone(v);
    return cone(ed.a);
  }
  // Side (+1 left, −1 right) of vertex v when crossing edge e along normal n.
  int crossing_side(int v, int e, const Vec2& n) const { return cross2(n, cone(v) - midpoint(e)) > 0 ? 1 : -1; }

  // The walk from node u across edge f into the next triangle; false when the step is implausible.
  bool step(int u, const Node& nu, int f, Node& nn) const {
    const auto& e = tri_.edges[static_cast<std::size_t>(f)];
    const Vec2 m = midpoint(f);
    Vec2 n = edge_normal(f);
    if (n.dot(m - third_vertex(nu.next_tri, f)) < 0) n = -n;
    const Vec2 d = m - nu.m;
    const double len = d.norm();
    const Vec2 across = cone(e.b) - cone(e.a);
    double heading = nu.heading, turn = 0, width = -1;
    if (len > 0.3) {
      heading = std::atan2(d.y(), d.x());
      turn = wrap_angle(heading - nu.heading);
      width = std::abs(cross2(d / len, across));
      // A crossing edge lies across the direction of travel (radial in a hairpin, diagonal between staggered
      // cones); one nearly along it is a boundary seen from an angle.
      if (width < c_.min_crossing_cos * across.norm()) return false;
    }
    if (std::abs(turn) > deg2rad(c_.max_turn_deg)) return false;
    if (revisits_or_flips(u, f, n)) return false;
    nn.edge = f;
    nn.next_tri = e.other(nu.next_tri);
    nn.parent = u;
    nn.m = m;
    nn.normal = n;
    nn.heading = heading;
    nn.length = nu.length + len;
    // A short step moves the path little sideways whatever its turn (hairpin fans, the last crossing at the
    // edge of what is seen), so its turn costs in proportion.
    nn.colour_cost = nu.colour_cost;
    nn.conflicts = nu.conflicts;
    nn.cost = nu.cost + c_.w_turn * turn * turn * std::min(1.0, len / 1.5) + side_cost(nn, f, n);
    nn.last = nu.last;
    nn.prev = nu.prev;
    nn.cost += boundary_cost(nn, f, n);
    nn.width_ref = nu.width_ref;
    if (width >= 0) {
      const double rel = (width - nu.width_ref) / nu.width_ref;
      nn.cost += c_.w_width * rel * rel;
      nn.width_ref = 0.7 * nu.width_ref + 0.3 * width;
    }
    return true;
  }

  // Extends the walk's boundaries by the cones of edge e and returns the cost of their shape: a boundary
  // bends gently from cone to cone, even round a hairpin's apex, and its cones are a few metres apart. A sharp
  // bend or a long gap means the walk slipped across a boundary (the colour-blind failure: crossing between two
  // cones of one side, or into the next stretch of a tightly packed track).
  double boundary_cost(Node& nn, int e, const Vec2& n) const {
    const auto& ed = tri_.edges[static_cast<std::size_t>(e)];
    double cost = 0;
    for (const int v : {ed.a, ed.b}) {
      const std::size_t k = crossing_side(v, e, n) > 0 ? 0 : 1;
      if (nn.last[k] == v) continue;
      if (nn.last[k] >= 0) {
        const double gap = std::max(0.0, (cone(v) - cone(nn.last[k])).norm() - c_.boundary_spacing_max);
        cost += c_.w_boundary_gap * gap * gap;
      }
      if (nn.last[k] >= 0 && nn.prev[k] >= 0) {
        const Vec2 a = cone(nn.last[k]) - cone(nn.prev[k]), b = cone(v) - cone(nn.last[k]);
        if (a.norm() > 1e-6 && b.norm() > 1e-6) {
          const double bend = std::abs(signed_angle(a, b));
          const double excess = std::max(0.0, bend - deg2rad(c_.boundary_free_bend_deg));
          cost += c_.w_boundary_bend * excess * excess;
        }
      }
      nn.prev[k] = nn.last[k];
      nn.last[k] = v;
    }
    return cost;
  }

  // Cost of the colours of edge e's cones for a crossing along n; accounted in nn's colour bookkeeping.
  double side_cost(Node& nn, int e, const Vec2& n) const {
    const auto& ed = tri_.edges[static_cast<std::size_t>(e)];
    double cost = 0;
    for (const int v : {ed.a, ed.b}) {
      const int known = cones_[static_cast<std::size_t>(v)].side;
      if (known == 0) {
        cost += c_.w_unknown;
      } else if (known != crossing_side(v, e, n)) {
        cost += c_.w_colour_conflict;
        ++nn.conflicts;
      }
    }
    nn.colour_cost += cost;
    return cost;
  }

  // A walk may not cross an edge twice nor pass a cone on both sides (it would be going round it).
  bool revisits_or_flips(int u, int e, const Vec2& n) const {
    const auto& ed = tri_.edges[static_cast<std::size_t>(e)];
    const int sa = crossing_side(ed.a, e, n), sb = crossing_side(ed.b, e, n);
    for (int w = u; w >= 0; w = nodes_[static_cast<std::size_t>(w)].parent) {
      const Node& nw = nodes_[static_cast<std::size_t>(w)];
      if (nw.edge == e) return true;
      const auto& ew = tri_.edges[static_cast<std::size_t>(nw.edge)];
      for (const int v : {ew.a, ew.b}) {
        if (v == ed.a && crossing_side(v, nw.edge, nw.normal) != sa) return true;
        if (v == ed.b && crossing_side(v, nw.edge, nw.normal) != sb) return true;
      }
    }
    return false;
  }

  double score(int id) const {
    const Node& n = nodes_[static_cast<std::size_t>(id)];
    return n.cost - c_.w_length * std::min(n.length, c_.horizon);
  }

  int push(const Node& n) {
    nodes_.push_back(n);
    return static_cast<int>(nodes_.size()) - 1;
  }

  // First crossings: edges ahead of the car, entered from the car's side.
  void seed() {
    const double max_bearing = deg2rad(c_.start_angle_deg);
    std::vector<int> seeds;
    for (std::size_t i = 0; i < tri_.edges.size(); ++i) {
      if (!crossable_[i]) continue;
      const int f = static_cast<int>(i);
      const Vec2 m = midpoint(f);
      const double dist = m.norm();
      if (m.x() <= 0 || dist > c_.start_radius || std::abs(std::atan2(m.y(), m.x())) > max_bearing) continue;
      Vec2 n = edge_normal(f);
      if (n.dot(m) < 0) n = -n;  // away from the car
      const auto& e = tri_.edges[i];
      int next = -1;
      for (const int t : e.tri)
        if (t >= 0 && n.dot(third_vertex(t, f) - m) > 0) next = t;
      Node nn;
      nn.edge = f;
      nn.next_tri = next;
      nn.m = m;
      nn.normal = n;
      nn.heading = std::atan2(m.y(), m.x());
      nn.length = dist;
      nn.width_ref = c_.nominal_width;
      boundary_cost(nn, f, n);
      const double w = std::abs(cross2(m / std::max(dist, 1e-6), cone(e.b) - cone(e.a)));
      if (dist > 0.3 && w < c_.min_crossing_cos * (cone(e.b) - cone(e.a)).norm()) continue;
      const double rel = (w - c_.nominal_width) / c_.nominal_width;
      nn.cost = c_.w_turn * nn.heading * nn.heading + c_.w_start * dist + c_.w_width * rel * rel;
      nn.cost += side_cost(nn, f, n);
      seeds.push_back(push(nn));
    }
    std::sort(seeds.begin(), seeds.end(), [&](int a, int b) { return score(a) < score(b); });
    if (seeds.size() > static_cast<std::size_t>(c_.beam_width)) seeds.resize(static_cast<std::size_t>(c_.beam_width));
    beam_ = std::move(seeds);
  }

  const CorridorWalkConfig& c_;
  const std::vector<WalkCone>& cones_;
  const Triangulation& tri_;
  std::vector<bool> crossable_;
  std::vector<Node> nodes_;
  std::vector<int> beam_, finals_;
};

// Fallback where one boundary is missing over a stretch (cones knocked over, not yet seen): follow the
// boundary that is there, half a track width inside it. Cones of unknown colour count for the side of the car
// they are on. The chain runs forward from the car, cone to nearest cone ahead, without sharp bends.
std::vector<Vec2> boundary_offset_walk(const std::vector<WalkCone>& cones, const CorridorWalkConfig& c,
                                       std::vector<Vec2>* boundary, int* boundary_side) {
  const double half_width = 0.5 * c.nominal_width;
  std::vector<Vec2> best;
  for (const int side : {1, -1}) {
    std::vector<Vec2> pts;
    for (const auto& k : cones) {
      const int s = k.side != 0 ? k.side : (std::abs(k.p.y()) > 0.5 ? (k.p.y() > 0 ? 1 : -1) : 0);
      if (s == side && k.p.x() > -1.0) pts.push_back(k.p);
    }
    std::vector<Vec2> chain;
    Vec2 at = Vec2::Zero(), dir = Vec2::UnitX();
    std::vector<bool> used(pts.size(), false);
    for (;;) {
      int next = -1;
      double nd = c.width_max + 1.0;  // boundary cones are at most a few metres apart
      for (std::size_t i = 0; i < pts.size(); ++i) {
        if (used[i]) continue;
        const Vec2 d = pts[i] - at;
        const double dist = d.norm();
        const bool first = chain.empty();
        // First cone: beside or ahead of the car on its side; then the next one ahead within a 60° bend.
        const bool ok = first ? (pts[i].x() < c.start_radius && dist < c.start_radius + 2.0)
                              : (dist > 0.5 && d.dot(dir) > std::cos(deg2rad(60.0)) * dist);
        if (ok && dist < nd) {
          nd = dist;
          next = static_cast<int>(i);
        }
      }
      if (next < 0) break;
      used[static_cast<std::size_t>(next)] = true;
      const Vec2 p = pts[static_cast<std::size_t>(next)];
      if (!chain.empty()) dir = (p - chain.back()).normalized();
      chain.push_back(p);
      at = p;
    }
    if (chain.size() < 2) continue;
    std::vector<Vec2> offset;
    for (std::size_t i = 0; i < chain.size(); ++i) {
      const Vec2 t = (chain[std::min(i + 1, chain.size() - 1)] - chain[i == 0 ? 0 : i - 1]).normalized();
      const Vec2 inward = -side * Vec2(-t.y(), t.x());  // away from the boundary, into the track
      offset.push_back(chain[i] + inward * half_width);
    }
    if (offset.size() > best.size()) {
      best = std::move(offset);
      *boundary = chain;
      *boundary_side = side;
    }
  }
  return best;
}

}  // namespace

double length_from_origin(const std::vector<Vec2>& points) {
  double len = 0;
  Vec2 at = Vec2::Zero();
  for (const Vec2& p : points) len += (p - at).norm(), at = p;
  return len;
}

namespace {
// The cones a walk passed on each side, in order, each once.
void boundaries_of(const std::vector<WalkCone>& cones, const std::vector<std::pair<int, int>>& passed,
                   CorridorWalk& out) {
  for (const auto& [cone, side] : passed) {
    auto& line = side > 0 ? out.left : out.right;
    const Vec2& p = cones[static_cast<std::size_t>(cone)].p;
    if (std::find_if(line.begin(), line.end(), [&](const Vec2& q) { return (q - p).squaredNorm() < 1e-12; }) ==
        line.end())
      line.push_back(p);
  }
}
}  // namespace

CorridorWalk walk_corridor(const std::vector<WalkCone>& cones, const CorridorWalkConfig& config) {
  CorridorWalk out;
  std::vector<Vec2> positions;
  positions.reserve(cones.size());
  for (const auto& c : cones) positions.push_back(c.p);
  const Triangulation tri = delaunay(positions);
  out.triangles = static_cast<int>(tri.triangles.size());
  Walk walk = Walker(config, cones, tri).walk();
  // A wrong colour can lead the walk astray where geometry alone would not: walk again without colours and
  // take that walk when its geometry is clearly better, or when a wrong colour stopped the coloured walk short
  // of where it could drive and the blind one goes on, as long as it passes no more than a cone or two against
  // their colour (more would be a wrong branch, not a wrong cone). Either beats falling back to one boundary.
  if (config.use_colours && config.colour_check_margin >= 0) {
    std::vector<WalkCone> blind = cones;
    for (auto& c : blind) c.side = 0;
    Walk geometric = Walker(config, blind, tri).walk();
    std::set<int> against;
    for (const auto& [cone, side] : geometric.passed)
      if (cones[static_cast<std::size_t>(cone)].side * side == -1) against.insert(cone);
    const bool better =
        !walk.mids.empty() && geometric.geometric_score + config.colour_check_margin < walk.geometric_score;
    const bool only_blind_leads = length_from_origin(walk.mids) < config.fallback_below &&
                                  length_from_origin(geometric.mids) >= config.fallback_below;
    if (!geometric.mids.empty() && static_cast<int>(against.size()) <= config.max_wrong_colours &&
        (better || only_blind_leads)) {
      walk = std::move(geometric);
      out.ignored_colours = true;
    }
  }
  const double length = length_from_origin(walk.mids);
  if (length < config.fallback_below) {
    std::vector<Vec2> side_line;
    int side = 0;
    std::vector<Vec2> offset = boundary_offset_walk(cones, config, &side_line, &side);
    if (!offset.empty() && length_from_origin(offset) > length + 1.0) {
      out.mids = std::move(offset);
      (side > 0 ? out.left : out.right) = std::move(side_line);
      out.single_boundary = true;
      return out;
    }
  }
  out.mids = std::move(walk.mids);
  std::reverse(walk.passed.begin(), walk.passed.end());
  boundaries_of(cones, walk.passed, out);
  return out;
}

}  // namespace fsd
