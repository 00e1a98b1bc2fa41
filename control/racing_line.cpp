#include "control/racing_line.hpp"

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>

namespace fsd {

namespace {

// One QP on the line linearised about `ref`: moving point i by α_i along its normal gives the curvature
// κ_i + κ_i² α_i + (α_{i−1} − 2α_i + α_{i+1}) / ds² to first order (an offset curve's curvature; the κ² term is
// what makes a constant offset outward in a bend flatter). Minimises Σ of its squares (+ ε|α|², so that a
// straight keeps its place) with lo ≤ α ≤ hi, by ADMM with the matrix factored once.
Eigen::VectorXd solve_step(const Path& ref, const Eigen::VectorXd& lo, const Eigen::VectorXd& hi, double ds,
                           bool& converged) {
  const auto n = static_cast<Eigen::Index>(ref.points.size());
  // Scaled by ds² so that the second difference has entries 1, −2, 1.
  std::vector<Eigen::Triplet<double>> trip;
  trip.reserve(static_cast<std::size_t>(n) * 3);
  Eigen::VectorXd k0(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double k = ref.points[static_cast<std::size_t>(i)].kappa;
    k0(i) = k * ds * ds;
    trip.emplace_back(i, (i + n - 1) % n, 1.0);
    trip.emplace_back(i, i, -2.0 + k * k * ds * ds);
    trip.emplace_back(i, (i + 1) % n, 1.0);
  }
  Eigen::SparseMatrix<double> A(n, n);
  A.setFromTriplets(trip.begin(), trip.end());
  // ρ between the curvature operator's fast and slow modes: measured on epfl_track_1 (bench/control_bench
  // BM_LapBuild), about 100 iterations a pass; 10× smaller or larger takes 2–10× as many.
  // A millimetre of tolerance is far below what the car tracks. (A large ρ stops at once, stuck near its start:
  // its steps are tiny, not its error.)
  constexpr double kRho = 2e-3, kEps = 1e-7, kTolerance = 1e-3;
  constexpr int kMaxIterations = 5000;
  Eigen::SparseMatrix<double> H = Eigen::SparseMatrix<double>(A.transpose()) * A;
  for (Eigen::Index i = 0; i < n; ++i) H.coeffRef(i, i) += kEps + kRho;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(H);
  Eigen::VectorXd z = Eigen::VectorXd::Zero(n).cwiseMax(lo).cwiseMin(hi), u = Eigen::VectorXd::Zero(n);
  if (solver.info() != Eigen::Success) return z;
  const Eigen::VectorXd g = -(A.transpose() * k0);
  converged = false;
  for (int it = 0; it < kMaxIterations; ++it) {
    const Eigen::VectorXd alpha = solver.solve(g + kRho * (z - u));
    if (!alpha.allFinite()) break;
    const Eigen::VectorXd z_next = (alpha + u).cwiseMax(lo).cwiseMin(hi);
    u += alpha - z_next;
    const double primal = (alpha - z_next).cwiseAbs().maxCoeff(), dual = (z_next - z).cwiseAbs().maxCoeff();
    z = z_next;
    if (primal < kTolerance && dual < kTolerance) {
      converged = true;
      break;
    }
  }
  return z;  // inside the box whether or not ADMM converged
}

}  // namespace

RacingLineResult minimum_curvature_line(const Path& centre, const std::vector<double>& room_left,
                                        const std::vector<double>& room_right) {
  RacingLineResult r;
  r.path = centre;
  const auto n = static_cast<Eigen::Index>(centre.points.size());
  if (!centre.closed || n < 8 || room_left.size() != centre.points.size() || room_right.size() != centre.points.size())
    return r;
  const double ds = centre.length() / static_cast<double>(n);
  // The total offset from the centre line, kept inside the room; re-linearised about the moved line a few times.
  Eigen::VectorXd total = Eigen::VectorXd::Zero(n);
  constexpr int kLinearisations = 3;
  r.converged = true;
  for (int pass = 0; pass < kLinearisations; ++pass) {
    Eigen::VectorXd lo(n), hi(n);
    for (Eigen::Index i = 0; i < n; ++i) {
      lo(i) = -std::max(0.0, room_right[static_cast<std::size_t>(i)]) - total(i);
      hi(i) = std::max(0.0, room_left[static_cast<std::size_t>(i)]) - total(i);
    }
    bool ok = false;
    const Eigen::VectorXd step = solve_step(r.path, lo, hi, ds, ok);
    r.converged = r.converged && ok;
    for (Eigen::Index i = 0; i < n; ++i) {
      auto& q = r.path.points[static_cast<std::size_t>(i)];
      q.p += step(i) * Vec2(-std::sin(q.yaw), std::cos(q.yaw));
    }
    total += step;
    compute_geometry(r.path);
  }
  r.max_offset = total.cwiseAbs().maxCoeff();
  return r;
}

}  // namespace fsd
