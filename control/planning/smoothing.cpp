#include "control/planning/smoothing.hpp"

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>
#include <cmath>
#include <numbers>

namespace fsd {

double whittaker_lambda(double cutoff_wavelength, double ds) {
  if (!(cutoff_wavelength > 0) || !(ds > 0)) return 0.0;
  // Transfer function of the second-difference smoother: H(ω) = 1 / (1 + λ(2 − 2cos ω)²); H = ½ at the cutoff.
  const double w = 2.0 * std::numbers::pi * ds / cutoff_wavelength;
  const double g = 2.0 - 2.0 * std::cos(std::min(w, std::numbers::pi));
  return 1.0 / (g * g);
}

namespace {

// I + λ·DᵀD for the second-difference operator D (rows 1, −2, 1; a closed loop wraps round), plus `extra` on the
// diagonal.
Eigen::SparseMatrix<double> whittaker_matrix(Eigen::Index n, bool closed, double lambda, double extra) {
  const Eigen::Index rows = closed ? n : n - 2;
  std::vector<Eigen::Triplet<double>> trip;
  trip.reserve(static_cast<std::size_t>(rows) * 3);
  for (Eigen::Index r = 0; r < rows; ++r) {
    trip.emplace_back(r, r % n, 1.0);
    trip.emplace_back(r, (r + 1) % n, -2.0);
    trip.emplace_back(r, (r + 2) % n, 1.0);
  }
  Eigen::SparseMatrix<double> D(rows, n);
  D.setFromTriplets(trip.begin(), trip.end());
  Eigen::SparseMatrix<double> A = Eigen::SparseMatrix<double>(D.transpose()) * D * lambda;
  for (Eigen::Index i = 0; i < n; ++i) A.coeffRef(i, i) += 1.0 + extra;
  return A;
}

Eigen::MatrixX2d to_matrix(const std::vector<Vec2>& points) {
  Eigen::MatrixX2d q(static_cast<Eigen::Index>(points.size()), 2);
  for (std::size_t i = 0; i < points.size(); ++i) q.row(static_cast<Eigen::Index>(i)) = points[i].transpose();
  return q;
}

std::vector<Vec2> to_points(const Eigen::MatrixX2d& p) {
  std::vector<Vec2> out(static_cast<std::size_t>(p.rows()));
  for (Eigen::Index i = 0; i < p.rows(); ++i) out[static_cast<std::size_t>(i)] = p.row(i).transpose();
  return out;
}

bool too_few(std::size_t n, bool closed, double lambda) { return n < 3 || !(lambda > 0) || (closed && n < 4); }

}  // namespace

std::vector<Vec2> whittaker_smooth(const std::vector<Vec2>& points, bool closed, double lambda) {
  if (too_few(points.size(), closed, lambda)) return points;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(
      whittaker_matrix(static_cast<Eigen::Index>(points.size()), closed, lambda, 0.0));
  if (solver.info() != Eigen::Success) return points;
  const Eigen::MatrixX2d p = solver.solve(to_matrix(points));
  if (solver.info() != Eigen::Success || !p.allFinite()) return points;
  return to_points(p);
}

std::vector<Vec2> whittaker_smooth_within(const std::vector<Vec2>& points, bool closed, double lambda, double radius) {
  if (too_few(points.size(), closed, lambda)) return points;
  if (!(radius > 0)) return points;
  // ADMM on min |p − c|² + λ|Dp|² subject to z = p, |z_i − c_i| ≤ radius: the p-step is one solve with the
  // matrix factored once, the z-step a clamp of each point into its disc.
  constexpr double kRho = 1.0;
  constexpr int kMaxIterations = 300;
  const double tolerance = 1e-3 * radius;
  const auto n = static_cast<Eigen::Index>(points.size());
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(whittaker_matrix(n, closed, lambda, kRho));
  if (solver.info() != Eigen::Success) return points;
  const Eigen::MatrixX2d c = to_matrix(points);
  Eigen::MatrixX2d z = c, u = Eigen::MatrixX2d::Zero(n, 2);
  auto clamp_rows = [&](Eigen::MatrixX2d m) {
    for (Eigen::Index i = 0; i < n; ++i) {
      const Eigen::RowVector2d d = m.row(i) - c.row(i);
      if (d.norm() > radius) m.row(i) = c.row(i) + d * (radius / d.norm());
    }
    return m;
  };
  for (int it = 0; it < kMaxIterations; ++it) {
    const Eigen::MatrixX2d p = solver.solve(c + kRho * (z - u));
    if (solver.info() != Eigen::Success || !p.allFinite()) return points;
    const Eigen::MatrixX2d z_next = clamp_rows(p + u);
    u += p - z_next;
    const double primal = (p - z_next).cwiseAbs().maxCoeff(), dual = (z_next - z).cwiseAbs().maxCoeff();
    z = z_next;
    if (primal < tolerance && dual < tolerance) break;
  }
  return to_points(z);
}

Path smooth_path(const Path& raw, double ds, double cutoff_wavelength, double radius) {
  Path uniform = resample(raw, ds);
  if (uniform.points.size() < 3) return uniform;
  std::vector<Vec2> pts;
  pts.reserve(uniform.points.size());
  for (const auto& p : uniform.points) pts.push_back(p.p);
  const double lambda = whittaker_lambda(cutoff_wavelength, ds);
  const auto smooth = radius > 0 ? whittaker_smooth_within(pts, uniform.closed, lambda, radius)
                                 : whittaker_smooth(pts, uniform.closed, lambda);
  Path out;
  out.stamp = raw.stamp;
  out.closed = raw.closed;
  out.points.resize(smooth.size());
  for (std::size_t i = 0; i < smooth.size(); ++i) out.points[i].p = smooth[i];
  compute_geometry(out);
  return out;
}

}  // namespace fsd
