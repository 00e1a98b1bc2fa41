#include "control/smoothing.hpp"

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

std::vector<Vec2> whittaker_smooth(const std::vector<Vec2>& points, bool closed, double lambda) {
  const auto n = static_cast<Eigen::Index>(points.size());
  if (n < 3 || !(lambda > 0)) return points;
  if (closed && n < 4) return points;
  // D: rows of (1, −2, 1); a closed loop wraps around.
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
  for (Eigen::Index i = 0; i < n; ++i) A.coeffRef(i, i) += 1.0;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(A);
  if (solver.info() != Eigen::Success) return points;
  Eigen::MatrixX2d q(n, 2);
  for (Eigen::Index i = 0; i < n; ++i) q.row(i) = points[static_cast<std::size_t>(i)].transpose();
  const Eigen::MatrixX2d p = solver.solve(q);
  if (solver.info() != Eigen::Success || !p.allFinite()) return points;
  std::vector<Vec2> out(points.size());
  for (Eigen::Index i = 0; i < n; ++i) out[static_cast<std::size_t>(i)] = p.row(i).transpose();
  return out;
}

Path smooth_path(const Path& raw, double ds, double cutoff_wavelength) {
  Path uniform = resample(raw, ds);
  if (uniform.points.size() < 3) return uniform;
  std::vector<Vec2> pts;
  pts.reserve(uniform.points.size());
  for (const auto& p : uniform.points) pts.push_back(p.p);
  const auto smooth = whittaker_smooth(pts, uniform.closed, whittaker_lambda(cutoff_wavelength, ds));
  Path out;
  out.stamp = raw.stamp;
  out.closed = raw.closed;
  out.points.resize(smooth.size());
  for (std::size_t i = 0; i < smooth.size(); ++i) out.points[i].p = smooth[i];
  compute_geometry(out);
  return out;
}

}  // namespace fsd
