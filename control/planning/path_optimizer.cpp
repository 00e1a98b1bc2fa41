#include "control/planning/path_optimizer.hpp"

#include <ceres/ceres.h>

#include <algorithm>
#include <cmath>

namespace fsd {

namespace {

// Shared geometry of the functors: node k's point for its offset, and the curvature of three points (Menger).
struct Node {
  Vec2 r, n;
  template <typename T>
  void at(const T& alpha, T& x, T& y) const {
    x = r.x() + alpha * n.x();
    y = r.y() + alpha * n.y();
  }
};

template <typename T>
T hinge(const T& v) {
  return v > T(0.0) ? v : T(0.0);
}

template <typename T>
T menger(const T& ax, const T& ay, const T& bx, const T& by, const T& cx, const T& cy) {
  using std::sqrt;
  const T ux = bx - ax, uy = by - ay, vx = cx - bx, vy = cy - by, wx = cx - ax, wy = cy - ay;
  const T denom = sqrt((ux * ux + uy * uy) * (vx * vx + vy * vy) * (wx * wx + wy * wy)) + T(1e-12);
  return T(2.0) * (ux * vy - uy * vx) / denom;
}

// κ at the middle of three nodes: its cost, the hard lock and the soft lock.
struct CurvatureCost {
  Node a, b, c;
  double w, kappa_hard, kappa_soft;
  const double* sqrt_penalty;
  double sqrt_soft;
  template <typename T>
  bool operator()(const T* aa, const T* ab, const T* ac, T* r) const {
    using std::abs;
    T ax, ay, bx, by, cx, cy;
    a.at(aa[0], ax, ay);
    b.at(ab[0], bx, by);
    c.at(ac[0], cx, cy);
    const T k = menger(ax, ay, bx, by, cx, cy);
    r[0] = T(w) * k;
    r[1] = T(*sqrt_penalty) * hinge(abs(k) - kappa_hard);
    r[2] = T(sqrt_soft) * hinge(abs(k) - kappa_soft);
    return true;
  }
};

// dκ/ds between two consecutive interior nodes (four nodes): its cost and its hard limit.
struct CurvatureRateCost {
  Node a, b, c, d;
  double w, rate_max;
  const double* sqrt_penalty;
  template <typename T>
  bool operator()(const T* aa, const T* ab, const T* ac, const T* ad, T* r) const {
    using std::abs;
    using std::sqrt;
    T ax, ay, bx, by, cx, cy, dx, dy;
    a.at(aa[0], ax, ay);
    b.at(ab[0], bx, by);
    c.at(ac[0], cx, cy);
    d.at(ad[0], dx, dy);
    const T k1 = menger(ax, ay, bx, by, cx, cy), k2 = menger(bx, by, cx, cy, dx, dy);
    const T len = sqrt((cx - bx) * (cx - bx) + (cy - by) * (cy - by)) + T(1e-9);
    const T rate = (k2 - k1) / len;
    r[0] = T(w) * rate;
    r[1] = T(*sqrt_penalty) * hinge(abs(rate) - rate_max);
    return true;
  }
};

// How an open path leaves its fixed first node: the tangent there of the circle through the first three nodes (the
// chord's direction less half the arc's angle) along the car's heading, and that circle's curvature the car's.
struct StartCost {
  Node a, b, c;
  double heading;
  const double* w_heading;
  double kappa, slack;
  const double* w_kappa;  // null: the curvature is free (the car steers in place)
  template <typename T>
  bool operator()(const T* ab, const T* ac, T* r) const {
    using std::atan2;
    using std::sqrt;
    T ax, ay, bx, by, cx, cy;
    a.at(T(0.0), ax, ay);
    b.at(ab[0], bx, by);
    c.at(ac[0], cx, cy);
    const T k = menger(ax, ay, bx, by, cx, cy);
    const T chord = sqrt((bx - ax) * (bx - ax) + (by - ay) * (by - ay));
    T diff = atan2(by - ay, bx - ax) - k * chord * T(0.5) - T(heading);
    const T two_pi(2.0 * 3.14159265358979323846);
    while (diff > T(3.14159265358979323846)) diff -= two_pi;
    while (diff < T(-3.14159265358979323846)) diff += two_pi;
    r[0] = T(*w_heading) * diff;
    using std::abs;
    r[1] = w_kappa ? T(*w_kappa) * hinge(abs(k - T(kappa)) - T(slack)) : T(0.0);
    return true;
  }
};

struct CentreCost {
  double w;
  template <typename T>
  bool operator()(const T* a, T* r) const {
    r[0] = T(w) * a[0];
    return true;
  }
};

// The body at a pose between two nodes (`t` of the way from p to q, heading along q − p) against one obstacle.
struct ChordClearanceCost {
  Node p, q;
  double t;
  Obstacle o;
  const Body* body;
  double hard, soft;
  const double* sqrt_penalty;
  double sqrt_soft;
  template <typename T>
  bool operator()(const T* ap, const T* aq, T* r) const {
    using std::atan2;
    T px, py, qx, qy;
    p.at(ap[0], px, py);
    q.at(aq[0], qx, qy);
    const T x = px + T(t) * (qx - px), y = py + T(t) * (qy - py);
    const T d = body_clearance(x, y, atan2(qy - py, qx - px), o.p.x(), o.p.y(), o.radius, *body);
    r[0] = T(*sqrt_penalty) * hinge(T(hard) - d);
    r[1] = T(sqrt_soft) * hinge(T(soft) - d);
    return true;
  }
};

// The body at a node, heading along the chord of its neighbours (the tangent of the arc through the three).
struct NodeClearanceCost {
  Node a, b, c;
  Obstacle o;
  const Body* body;
  double hard, soft;
  const double* sqrt_penalty;
  double sqrt_soft;
  template <typename T>
  bool operator()(const T* aa, const T* ab, const T* ac, T* r) const {
    using std::atan2;
    T ax, ay, bx, by, cx, cy;
    a.at(aa[0], ax, ay);
    b.at(ab[0], bx, by);
    c.at(ac[0], cx, cy);
    const T d = body_clearance(bx, by, atan2(cy - ay, cx - ax), o.p.x(), o.p.y(), o.radius, *body);
    r[0] = T(*sqrt_penalty) * hinge(T(hard) - d);
    r[1] = T(sqrt_soft) * hinge(T(soft) - d);
    return true;
  }
};

}  // namespace

PathOptimizer::PathOptimizer(PathOptimizerConfig config, Body body, double kappa_lock)
    : config_(config), body_(body), kappa_lock_(kappa_lock) {}

OptimizerOutput PathOptimizer::solve(const OptimizerInput& in, const std::vector<double>* start_alpha) const {
  OptimizerOutput out;
  const int n = static_cast<int>(in.reference.size());
  const auto un = static_cast<std::size_t>(n);
  if (n < 4 || in.normals.size() != un || in.lo.size() != un || in.hi.size() != un) return out;
  const PathOptimizerConfig& c = config_;
  const bool closed = in.closed;
  const int fixed = closed ? 0 : std::clamp(in.fixed, 0, n);

  // Spacing of the reference: the weights are per metre.
  double length = 0;
  for (std::size_t k = 1; k < un; ++k) length += (in.reference[k] - in.reference[k - 1]).norm();
  const double ds = std::max(1e-3, length / std::max(1, n - 1));
  // The hard constraints' weight, raised in stages (each solve starting from the last): a heavy penalty from the
  // start leaves the solver stuck where it began.
  double sqrt_pen = std::sqrt(std::min(c.penalty, 1e3));
  const double* pen = &sqrt_pen;
  const double kappa_hard = (1.0 - c.lock_margin) * kappa_lock_;
  const double kappa_soft = (1.0 - c.lock_margin_soft) * kappa_lock_;

  std::vector<double> alpha(un, 0.0);
  for (int i = 0; i < n; ++i) {
    const auto k = static_cast<std::size_t>(i);
    const double a0 = start_alpha && start_alpha->size() == un ? (*start_alpha)[k] : 0.0;
    alpha[k] = i < fixed ? 0.0 : std::clamp(a0, std::min(in.lo[k], in.hi[k]), std::max(in.lo[k], in.hi[k]));
  }
  std::vector<Node> nodes(un);
  for (std::size_t k = 0; k < un; ++k) nodes[k] = {in.reference[k], in.normals[k]};
  auto idx = [&](int i) { return static_cast<std::size_t>(closed ? (i % n + n) % n : i); };
  auto node = [&](int i) -> const Node& { return nodes[idx(i)]; };
  auto par = [&](int i) { return &alpha[idx(i)]; };

  // The body's pose at node i (heading along its neighbours' chord) and half-way to node i + 1, for the alpha of now.
  auto point = [&](int i) { return node(i).r + alpha[idx(i)] * node(i).n; };
  auto node_pose = [&](int i) {
    const Vec2 a = (closed || i > 0) ? point(i - 1) : point(i), b = (closed || i < n - 1) ? point(i + 1) : point(i);
    const Vec2 p = point(i), d = b - a;
    return Pose2{p.x(), p.y(), std::atan2(d.y(), d.x())};
  };
  auto chord_pose = [&](int i) {
    const Vec2 a = point(i), b = point(i + 1), m = 0.5 * (a + b), d = b - a;
    return Pose2{m.x(), m.y(), std::atan2(d.y(), d.x())};
  };
  // Which node (and chord) may meet which obstacle: by distance from the reference, once.
  const double soft = std::max(c.clearance_soft, c.clearance);
  struct Pair {
    int i;
    std::size_t o;
  };
  std::vector<Pair> candidates;
  double s_along = 0;
  for (int i = 0; i < n; ++i) {
    if (i > 0) s_along += (node(i).r - node(i - 1).r).norm();
    if (!closed && s_along < in.free_from) continue;
    const auto k = static_cast<std::size_t>(i);
    const double within = body_.reach() + std::max(std::abs(in.lo[k]), std::abs(in.hi[k])) + soft + ds;
    for (std::size_t o = 0; o < in.obstacles.size(); ++o)
      if ((in.obstacles[o].p - node(i).r).norm() <= within + in.obstacles[o].radius) candidates.push_back({i, o});
  }

  ceres::Solver::Options so;
  // Each residual touches at most four nodes: the normal equations are banded, sparse at any length.
  so.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  so.max_num_iterations = c.max_iterations;
  so.num_threads = 1;
  so.logging_type = ceres::SILENT;
  so.minimizer_progress_to_stdout = false;
  so.function_tolerance = 1e-8;
  so.parameter_tolerance = 1e-7;
  const double sqrt_soft = std::sqrt(c.w_clearance_soft * ds * 0.5);  // two poses per node
  out.converged = true;
  // The stages: each a problem of its own, with the clearance terms only of the pairs whose body comes within reach
  // of costing from where the last stage left it (the first stage: as far as the offsets and turning could bring
  // them). Far pairs cost nothing and only slow the solver; the exact sweep after the optimizer checks them all.
  for (int stage = 0;; ++stage) {
    const double weight = std::min(c.penalty, 1e3 * std::pow(100.0, stage));
    sqrt_pen = std::sqrt(weight);
    const double reach_in = stage == 0 ? 1.5 : 0.3;  // m beyond the soft clearance a pair is kept
    ceres::Problem::Options po;
    po.cost_function_ownership = ceres::TAKE_OWNERSHIP;
    ceres::Problem problem(po);
    for (int i = 0; i < n; ++i) problem.AddParameterBlock(par(i), 1);
    for (int i = 0; i < n; ++i) {
      const auto k = static_cast<std::size_t>(i);
      const double lo = std::min(in.lo[k], in.hi[k]), hi = std::max(in.lo[k], in.hi[k]);
      if (i < fixed || hi - lo < 1e-6) {
        problem.SetParameterBlockConstant(par(i));
        continue;
      }
      problem.SetParameterLowerBound(par(i), 0, lo);
      problem.SetParameterUpperBound(par(i), 0, hi);
      problem.AddResidualBlock(
          new ceres::AutoDiffCostFunction<CentreCost, 1, 1>(new CentreCost{std::sqrt(c.w_centre * ds)}), nullptr,
          par(i));
    }
    const int first = closed ? 0 : 1, last = closed ? n - 1 : n - 2;  // nodes with two neighbours
    for (int i = first; i <= last; ++i) {
      auto* f = new CurvatureCost{node(i - 1), node(i),    node(i + 1), std::sqrt(c.w_curvature * ds),
                                  kappa_hard,  kappa_soft, pen,         std::sqrt(c.w_lock_soft * ds)};
      problem.AddResidualBlock(new ceres::AutoDiffCostFunction<CurvatureCost, 3, 1, 1, 1>(f), nullptr, par(i - 1),
                               par(i), par(i + 1));
    }
    const int rate_last = closed ? n - 1 : n - 3;
    const int rate_first = closed ? 0 : std::max(first, static_cast<int>(std::ceil(in.rate_free_until / ds)));
    for (int i = rate_first; i <= rate_last; ++i) {
      auto* f = new CurvatureRateCost{
          node(i - 1), node(i), node(i + 1), node(i + 2), std::sqrt(c.w_curvature_rate * ds), c.kappa_rate_max, pen};
      problem.AddResidualBlock(new ceres::AutoDiffCostFunction<CurvatureRateCost, 2, 1, 1, 1, 1>(f), nullptr,
                               par(i - 1), par(i), par(i + 1), par(i + 2));
    }
    if (!closed && in.start_heading && fixed == 1 && n > 2) {
      auto* f = new StartCost{node(0),
                              node(1),
                              node(2),
                              *in.start_heading,
                              pen,
                              in.start_kappa.value_or(0.0),
                              in.start_kappa_slack,
                              in.start_kappa ? pen : nullptr};
      problem.AddResidualBlock(new ceres::AutoDiffCostFunction<StartCost, 2, 1, 1>(f), nullptr, par(1), par(2));
    }
    for (const Pair& pr : candidates) {
      const int i = pr.i;
      const Obstacle& o = in.obstacles[pr.o];
      const bool has_prev = closed || i > 0, has_next = closed || i < n - 1;
      const double keep =
          soft + reach_in + (stage == 0 ? std::max(std::abs(in.lo[idx(i)]), std::abs(in.hi[idx(i)])) : 0);
      if (has_prev && has_next && body_clearance(node_pose(i), o, body_) < keep) {
        auto* f =
            new NodeClearanceCost{node(i - 1), node(i), node(i + 1), o, &body_, c.clearance, soft, pen, sqrt_soft};
        problem.AddResidualBlock(new ceres::AutoDiffCostFunction<NodeClearanceCost, 2, 1, 1, 1>(f), nullptr, par(i - 1),
                                 par(i), par(i + 1));
      }
      if (has_next && body_clearance(chord_pose(i), o, body_) < keep) {
        auto* f = new ChordClearanceCost{node(i), node(i + 1), 0.5, o, &body_, c.clearance, soft, pen, sqrt_soft};
        problem.AddResidualBlock(new ceres::AutoDiffCostFunction<ChordClearanceCost, 2, 1, 1>(f), nullptr, par(i),
                                 par(i + 1));
      }
    }
    ceres::Solver::Summary summary;
    ceres::Solve(so, &problem, &summary);
    out.converged = out.converged && summary.termination_type == ceres::CONVERGENCE;
    out.iterations += static_cast<int>(summary.iterations.size());
    out.cost = summary.final_cost;
    if (weight >= c.penalty) break;
  }
  out.alpha = alpha;
  out.points.resize(un);
  for (std::size_t k = 0; k < un; ++k) out.points[k] = in.reference[k] + alpha[k] * in.normals[k];
  return out;
}

}  // namespace fsd
