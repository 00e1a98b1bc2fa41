#include "control/planning/arc_path.hpp"

namespace fsd {

namespace {
// Signed curvature of the circle through three points (left turns positive); 0 for coincident or straight ones.
double menger(const Vec2& a, const Vec2& b, const Vec2& c) {
  const double den = (b - a).norm() * (c - b).norm() * (c - a).norm();
  return den > 1e-12 ? 2.0 * cross2(b - a, c - b) / den : 0.0;
}
}  // namespace

Path arc_path(const std::vector<Vec2>& nodes, bool closed) {
  Path out;
  out.closed = closed;
  const std::size_t n = nodes.size();
  if (n < 3) {
    for (const auto& p : nodes) out.points.push_back({p, 0, 0, 0, 0});
    compute_geometry(out);
    return out;
  }
  std::vector<double> kappa(n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    if (!closed && (i == 0 || i == n - 1)) continue;
    kappa[i] = menger(nodes[(i + n - 1) % n], nodes[i], nodes[(i + 1) % n]);
  }
  if (!closed) kappa.front() = kappa[1], kappa.back() = kappa[n - 2];
  const std::size_t segments = closed ? n : n - 1;
  std::vector<double> point_kappa;
  for (std::size_t i = 0; i < segments; ++i) {
    const Vec2& a = nodes[i];
    const Vec2& b = nodes[(i + 1) % n];
    out.points.push_back({a, 0, 0, 0, 0});
    point_kappa.push_back(kappa[i]);
    const Vec2 chord = b - a;
    const double c = chord.norm();
    if (c < 1e-9) continue;
    const double k = 0.5 * (kappa[i] + kappa[(i + 1) % n]);
    const Vec2 left(-chord.y() / c, chord.x() / c);
    // A left turn's arc bulges to the right of its chord (away from the centre).
    out.points.push_back({0.5 * (a + b) - k * c * c / 8.0 * left, 0, 0, 0, 0});
    point_kappa.push_back(k);
  }
  if (!closed) {
    out.points.push_back({nodes.back(), 0, 0, 0, 0});
    point_kappa.push_back(kappa.back());
  }
  compute_geometry(out);
  // The curvature is the nodes' own (what the optimizer bounded) and their mean between: three neighbours of unequal
  // curvature would give a point a circle the path does not have where the curvature changes fast.
  for (std::size_t i = 0; i < out.points.size(); ++i) out.points[i].kappa = point_kappa[i];
  return out;
}

}  // namespace fsd
