#include "control/missions/skidpad.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "control/planning/smoothing.hpp"

namespace fsd {

namespace {

// Algebraic (Kåsa) circle fit: |p|² = 2c·p + (r² − |c|²), linear in c and the constant.
std::optional<Vec2> kasa_centre(const std::vector<Vec2>& pts) {
  if (pts.size() < 3) return std::nullopt;
  Eigen::MatrixXd A(static_cast<Eigen::Index>(pts.size()), 3);
  Eigen::VectorXd b(static_cast<Eigen::Index>(pts.size()));
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const auto k = static_cast<Eigen::Index>(i);
    A(k, 0) = 2 * pts[i].x();
    A(k, 1) = 2 * pts[i].y();
    A(k, 2) = 1;
    b(k) = pts[i].squaredNorm();
  }
  const Eigen::Vector3d x = A.colPivHouseholderQr().solve(b);
  if (!x.allFinite()) return std::nullopt;
  return Vec2(x(0), x(1));
}

// Two concentric rings: the split into inner and outer by distance from the current centre, then one linear
// fit of the shared centre and both radii; a few rounds settle the split. A cone that is not on either ring (a
// ghost, a cone of the entry or exit lane, one whose colour was misread so that it counts on the wrong side) would
// pull a least-squares fit by metres: each round leaves out the cones farther from their ring than three times the
// median distance (at least `kRingTolerance`), and the fit is refused when fewer than three stay on a ring.
constexpr double kRingTolerance = 0.5;                    // m
constexpr double kMaxUnseenArc = 0.6 * std::numbers::pi;  // rad of a circle with no cone kept on it

std::optional<SkidpadCircle> fit_rings(const std::vector<Vec2>& pts) {
  auto centre = kasa_centre(pts);
  if (!centre || pts.size() < 6) return std::nullopt;
  SkidpadCircle c;
  std::vector<bool> use(pts.size(), true);
  double split = 0;
  for (int round = 0; round < 8; ++round) {
    std::vector<double> d;
    for (const auto& p : pts) d.push_back((p - *centre).norm());
    if (round == 0) {  // between the quartiles of the distances: a stray cone at the centre or far out does not move it
      std::vector<double> sorted = d;
      std::sort(sorted.begin(), sorted.end());
      split = 0.5 * (sorted[sorted.size() / 4] + sorted[sorted.size() * 3 / 4]);
    } else {  // between the fitted radii; and what lies off both rings is left out, the bound shrinking as it settles
      split = 0.5 * (c.inner_radius + c.outer_radius);
      std::vector<double> res(pts.size()), kept;
      for (std::size_t i = 0; i < pts.size(); ++i) {
        res[i] = std::abs(d[i] - (d[i] < split ? c.inner_radius : c.outer_radius));
        if (use[i]) kept.push_back(res[i]);
      }
      std::nth_element(kept.begin(), kept.begin() + static_cast<std::ptrdiff_t>(kept.size() / 2), kept.end());
      const double bound = std::max(kRingTolerance, 3.0 * kept[kept.size() / 2]);
      for (std::size_t i = 0; i < pts.size(); ++i) use[i] = res[i] <= bound;
    }
    Eigen::MatrixXd A(static_cast<Eigen::Index>(pts.size()), 4);
    Eigen::VectorXd b(static_cast<Eigen::Index>(pts.size()));
    int inner = 0, outer = 0;
    for (std::size_t i = 0; i < pts.size(); ++i) {
      const auto k = static_cast<Eigen::Index>(i);
      const bool in = d[i] < split;
      const double w = use[i] ? 1.0 : 0.0;
      inner += use[i] && in;
      outer += use[i] && !in;
      A.row(k) << w * 2 * pts[i].x(), w * 2 * pts[i].y(), w * (in ? 1.0 : 0.0), w * (in ? 0.0 : 1.0);
      b(k) = w * pts[i].squaredNorm();
    }
    if (inner < 3 || outer < 3) return std::nullopt;
    const Eigen::Vector4d x = A.colPivHouseholderQr().solve(b);
    if (!x.allFinite()) return std::nullopt;
    *centre = Vec2(x(0), x(1));
    const double r2_in = x(2) + centre->squaredNorm(), r2_out = x(3) + centre->squaredNorm();
    if (r2_in <= 0 || r2_out <= 0) return std::nullopt;
    c.inner_radius = std::sqrt(r2_in);
    c.outer_radius = std::sqrt(r2_out);
  }
  // Rings fitted to a short arc can have any size and centre: no arc wider than kMaxUnseenArc may be without a cone.
  std::vector<double> angles;
  for (std::size_t i = 0; i < pts.size(); ++i)
    if (use[i]) angles.push_back(std::atan2(pts[i].y() - centre->y(), pts[i].x() - centre->x()));
  std::sort(angles.begin(), angles.end());
  double widest_gap = angles.front() + 2 * std::numbers::pi - angles.back();
  for (std::size_t i = 1; i < angles.size(); ++i) widest_gap = std::max(widest_gap, angles[i] - angles[i - 1]);
  if (widest_gap > kMaxUnseenArc) return std::nullopt;
  c.centre = *centre;
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
  if (std::abs(d - 18.25) > 2.0) return fail("circle centres " + std::to_string(d) + " m apart (expected ~18.25 m)");
  g.forward = Vec2(across.y(), -across.x()) / d;
  if (g.forward.dot(Vec2(std::cos(start.yaw), std::sin(start.yaw))) < 0) g.forward = -g.forward;
  for (const auto* c : {&g.right, &g.left})
    if (std::abs(c->outer_radius - c->inner_radius - 3.0) > 1.0)
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
