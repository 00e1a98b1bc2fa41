#include "control/missions/skidpad.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "control/planning/smoothing.hpp"

namespace fsd {

namespace {

// The rules' skid pad: rings of 15.25 and 21.25 m diameter round each centre, the centres 18.25 m apart.
constexpr double kRulesInner = 7.625, kRulesOuter = 10.625, kRulesCentres = 18.25;  // m

// Where a circle's centre is, found by voting (a Hough transform for circles of known radius): every cone votes for
// the cells its rings could be centred on, each cell counts the cones that voted for it. A least-squares fit from
// the cones' mean is pulled by metres by one cone that is on neither ring (an entry-lane cone whose colour was
// misread, a ghost) when only the near arcs are seen; the vote is not.
constexpr double kVoteCell = 0.5;       // m
constexpr double kVoteTolerance = 0.4;  // m: a cone votes for cells whose centre is this close to one of its rings

std::optional<Vec2> vote_centre(const std::vector<Vec2>& pts) {
  if (pts.empty()) return std::nullopt;
  Vec2 lo = pts.front(), hi = pts.front();
  for (const auto& p : pts) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const double reach = kRulesOuter + kVoteTolerance;
  lo.array() -= reach;
  hi.array() += reach;
  const int nx = static_cast<int>(std::ceil((hi.x() - lo.x()) / kVoteCell));
  const int ny = static_cast<int>(std::ceil((hi.y() - lo.y()) / kVoteCell));
  if (nx <= 0 || ny <= 0 || static_cast<long>(nx) * ny > 4'000'000) return std::nullopt;  // cones kilometres apart
  std::vector<int> votes(static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny), 0);
  const int span = static_cast<int>(std::ceil(reach / kVoteCell));
  for (const auto& p : pts) {
    const int ix0 = static_cast<int>((p.x() - lo.x()) / kVoteCell),
              iy0 = static_cast<int>((p.y() - lo.y()) / kVoteCell);
    for (int iy = std::max(0, iy0 - span); iy <= std::min(ny - 1, iy0 + span); ++iy) {
      const double dy = lo.y() + kVoteCell * (iy + 0.5) - p.y();
      // Only the cells of this row that can lie on a ring's band (|d − r| ≤ tolerance) are looked at: the two bands
      // are metres apart, so each cell is counted at most once, and a row's two arcs of one band once if they meet.
      for (const double r : {kRulesInner, kRulesOuter}) {
        const double outer = r + kVoteTolerance, inner = r - kVoteTolerance;
        if (std::abs(dy) > outer) continue;
        const double xo = std::sqrt(outer * outer - dy * dy);
        const double xi = inner > std::abs(dy) ? std::sqrt(inner * inner - dy * dy) : 0.0;
        const auto column = [&](double dx) { return (p.x() + dx - lo.x()) / kVoteCell - 0.5; };  // a cell at dx
        const auto vote = [&](int from, int to) {
          for (int ix = std::max({0, ix0 - span, from}); ix <= std::min({nx - 1, ix0 + span, to}); ++ix) {
            const Vec2 c = lo + kVoteCell * Vec2(ix + 0.5, iy + 0.5);
            if (std::abs((p - c).norm() - r) <= kVoteTolerance)
              ++votes[static_cast<std::size_t>(iy) * static_cast<std::size_t>(nx) + static_cast<std::size_t>(ix)];
          }
        };
        // The band's cells on this row: dx in [−xo, −xi] and [xi, xo], one run where the two meet.
        const int left_from = static_cast<int>(std::floor(column(-xo)));
        const int left_to = static_cast<int>(std::ceil(column(-xi)));
        const int right_from = static_cast<int>(std::floor(column(xi)));
        const int right_to = static_cast<int>(std::ceil(column(xo)));
        if (left_to >= right_from) {
          vote(left_from, right_to);
        } else {
          vote(left_from, left_to);
          vote(right_from, right_to);
        }
      }
    }
  }
  const auto best = std::max_element(votes.begin(), votes.end()) - votes.begin();
  return lo + kVoteCell * Vec2(best % nx + 0.5, best / nx + 0.5);
}

// Two concentric rings from the voted centre: each round splits the cones into inner and outer by the nearer ring,
// leaves out those farther from it than three times the median distance (at least `kRingTolerance`), and fits the
// shared centre and both radii to the rest (Gauss-Newton on the distances to the rings). Both radii carry the rules'
// value as a prior worth about one cone: a fit to a short arc keeps the rules' size, a skid pad marked a little off
// the rules (every cone of it) moves the radii. Refused when fewer than three cones stay on a ring.
constexpr double kRingTolerance = 0.5;                    // m
constexpr double kConeSigma = 0.1, kRadiusSigma = 0.1;    // m: a cone's place on its ring; the ring against the rules
constexpr double kMaxUnseenArc = 0.6 * std::numbers::pi;  // rad of a circle with no cone kept on it

std::optional<SkidpadCircle> fit_rings(const std::vector<Vec2>& pts) {
  if (pts.size() < 6) return std::nullopt;
  const auto voted = vote_centre(pts);
  if (!voted) return std::nullopt;
  Eigen::Vector4d x(voted->x(), voted->y(), kRulesInner, kRulesOuter);  // centre, inner and outer radius
  std::vector<bool> use(pts.size(), true);
  constexpr double prior = kConeSigma / kRadiusSigma;
  for (int round = 0; round < 6; ++round) {
    const Vec2 c(x(0), x(1));
    const double split = 0.5 * (x(2) + x(3));
    std::vector<double> res(pts.size()), kept;
    std::vector<bool> in(pts.size());
    for (std::size_t i = 0; i < pts.size(); ++i) {
      const double d = (pts[i] - c).norm();
      in[i] = d < split;
      res[i] = std::abs(d - (in[i] ? x(2) : x(3)));
      if (use[i]) kept.push_back(res[i]);
    }
    std::nth_element(kept.begin(), kept.begin() + static_cast<std::ptrdiff_t>(kept.size() / 2), kept.end());
    const double bound = std::max(kRingTolerance, 3.0 * kept[kept.size() / 2]);
    int inner = 0, outer = 0;
    for (std::size_t i = 0; i < pts.size(); ++i) {
      use[i] = res[i] <= bound;
      inner += use[i] && in[i];
      outer += use[i] && !in[i];
    }
    if (inner < 3 || outer < 3) return std::nullopt;
    for (int it = 0; it < 5; ++it) {
      Eigen::Matrix4d H = Eigen::Matrix4d::Zero();
      Eigen::Vector4d g = Eigen::Vector4d::Zero();
      for (std::size_t i = 0; i < pts.size(); ++i) {
        if (!use[i]) continue;
        const Vec2 v = pts[i] - Vec2(x(0), x(1));
        const double d = v.norm();
        if (d < 1e-6) continue;
        Eigen::Vector4d J(-v.x() / d, -v.y() / d, in[i] ? -1.0 : 0.0, in[i] ? 0.0 : -1.0);
        const double e = d - (in[i] ? x(2) : x(3));
        H += J * J.transpose();
        g += J * e;
      }
      for (int k : {2, 3}) {
        const double e = prior * (x(k) - (k == 2 ? kRulesInner : kRulesOuter));
        H(k, k) += prior * prior;
        g(k) += prior * e;
      }
      const Eigen::Vector4d step = H.ldlt().solve(-g);
      if (!step.allFinite()) return std::nullopt;
      x += step;
      if (step.norm() < 1e-6) break;
    }
    if (x(2) <= 0 || x(3) <= x(2)) return std::nullopt;
  }
  SkidpadCircle c;
  c.centre = Vec2(x(0), x(1));
  c.inner_radius = x(2);
  c.outer_radius = x(3);
  // Rings fitted to a short arc can have any size and centre: no arc wider than kMaxUnseenArc may be without a cone.
  std::vector<double> angles;
  for (std::size_t i = 0; i < pts.size(); ++i)
    if (use[i]) angles.push_back(std::atan2(pts[i].y() - c.centre.y(), pts[i].x() - c.centre.x()));
  std::sort(angles.begin(), angles.end());
  double widest_gap = angles.front() + 2 * std::numbers::pi - angles.back();
  for (std::size_t i = 1; i < angles.size(); ++i) widest_gap = std::max(widest_gap, angles[i] - angles[i - 1]);
  if (widest_gap > kMaxUnseenArc) return std::nullopt;
  c.cones = static_cast<int>(angles.size());
  return c;
}

}  // namespace

std::optional<SkidpadGeometry> fit_skidpad(const std::vector<Cone>& cones, const Pose2& start,
                                           const ColourConvention& convention, std::string* reason) {
  auto fail = [&](const std::string& why) -> std::optional<SkidpadGeometry> {
    if (reason) *reason = why;
    return std::nullopt;
  };
  std::vector<Vec2> right, left;
  for (const auto& c : cones) {
    if (!c.position.allFinite()) continue;
    const ConeRole role = convention.role_of(c.colour);
    if (role == ConeRole::Timing || role == ConeRole::Other) continue;
    const Vec2 m = c.position.head<2>();
    const double lateral = start.inverse_transform(m).y();
    if (std::abs(lateral) < 0.5) continue;  // on the entry axis: belongs to neither circle
    (lateral < 0 ? right : left).push_back(m);
  }
  const auto r = fit_rings(right);
  const auto l = fit_rings(left);
  if (!r) return fail("right circle: cannot fit two rings to " + std::to_string(right.size()) + " cones");
  if (!l) return fail("left circle: cannot fit two rings to " + std::to_string(left.size()) + " cones");
  SkidpadGeometry g;
  g.right = *r;
  g.left = *l;
  g.crossing = 0.5 * (r->centre + l->centre);
  const Vec2 across = l->centre - r->centre;  // right → left
  const double d = across.norm();
  // The rules fix the skid pad (centres 18.25 m apart, a 3 m lane between rings of 15.25 and 21.25 m diameter): a
  // fit far from that is of too little of the rings (from the entry lane the near arcs fit rings of any size), and
  // is refused until more of them is seen.
  if (std::abs(d - kRulesCentres) > 2.0)
    return fail("circle centres " + std::to_string(d) + " m apart (expected ~" + std::to_string(kRulesCentres) + " m)");
  g.forward = Vec2(across.y(), -across.x()) / d;
  if (g.forward.dot(Vec2(std::cos(start.yaw), std::sin(start.yaw))) < 0) g.forward = -g.forward;
  for (const auto* c : {&g.right, &g.left})
    if (std::abs(c->outer_radius - c->inner_radius - (kRulesOuter - kRulesInner)) > 1.0)
      return fail("ring radii implausible (" + std::to_string(c->inner_radius) + ", " +
                  std::to_string(c->outer_radius) + ")");
  return g;
}

SkidpadPlan skidpad_path(const SkidpadGeometry& g, const Pose2& start, double exit_length, double ds,
                         double transition) {
  SkidpadPlan plan;
  Path& p = plan.path;
  auto add = [&](const Vec2& q) {
    if (p.points.empty() || (q - p.points.back().p).norm() > 1e-6) p.points.push_back({q, 0, 0, 0, 0});
  };
  // Entry: from the start's foot on the axis through the crossing.
  const double before = std::min(-1.0, (start.position() - g.crossing).dot(g.forward));
  for (double s = before; s < 0; s += ds) add(g.crossing + s * g.forward);
  auto circle = [&](const Vec2& centre, bool clockwise) {
    const Vec2 r0 = g.crossing - centre;
    const double radius = r0.norm();
    const double a0 = std::atan2(r0.y(), r0.x());
    const int n = std::max(8, static_cast<int>(std::ceil(2 * std::numbers::pi * radius / ds)));
    for (int k = 0; k < n; ++k) {
      const double a = a0 + (clockwise ? -1 : 1) * 2 * std::numbers::pi * k / n;
      add(centre + radius * Vec2(std::cos(a), std::sin(a)));
    }
  };
  std::array<std::size_t, 5> idx{};
  idx[0] = p.points.size();
  circle(g.right.centre, true);
  idx[1] = p.points.size();
  circle(g.right.centre, true);
  idx[2] = p.points.size();
  circle(g.left.centre, false);
  idx[3] = p.points.size();
  circle(g.left.centre, false);
  idx[4] = p.points.size();
  for (double s = 0; s <= exit_length + 1e-9; s += ds) add(g.crossing + s * g.forward);
  // Points are (nearly) uniformly spaced, so the smoother keeps each index where it was along the figure.
  if (transition > 0) {
    std::vector<Vec2> pts;
    for (const auto& q : p.points) pts.push_back(q.p);
    pts = whittaker_smooth(pts, false, whittaker_lambda(transition, ds));
    for (std::size_t i = 0; i < pts.size(); ++i) p.points[i].p = pts[i];
  }
  compute_geometry(p);
  for (std::size_t k = 0; k < 5; ++k) plan.crossing_s[k] = p.points[std::min(idx[k], p.points.size() - 1)].s;
  return plan;
}

}  // namespace fsd
