#include "localization/lidar_odometry/registration.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

namespace fsd::lidar_odometry {

namespace {
// Rotations are scaled by this lever before the eigenvalues are compared with translations: a radian at 10 m
// moves a point as far as 10 m of translation.
constexpr double kLever = 10.0;

struct Normal {
  Matrix6d H = Matrix6d::Zero();
  Vec6 g = Vec6::Zero();
  double wr2 = 0;
  int n = 0;
};

double huber(double r, double delta) { return std::abs(r) <= delta ? 1.0 : delta / std::abs(r); }

// The k neighbours' centre and the eigen-decomposition of their scatter: the local line or plane they lie on.
struct LocalShape {
  Vec3 mean;
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig;
};
LocalShape local_shape(const std::vector<Vec3>& points, const std::size_t* idx, std::size_t k) {
  Vec3 mean = Vec3::Zero();
  for (std::size_t i = 0; i < k; ++i) mean += points[idx[i]];
  mean /= double(k);
  Eigen::Matrix3d C = Eigen::Matrix3d::Zero();
  for (std::size_t i = 0; i < k; ++i) C += (points[idx[i]] - mean) * (points[idx[i]] - mean).transpose();
  LocalShape out{mean, {}};
  out.eig.computeDirect(C);  // closed form for 3×3: several times faster than the iterative solver
  return out;
}
}  // namespace

Pose3 motion(const Vec6& delta, double s) {
  Pose3 D = Pose3::Identity();
  const Vec3 w = delta.tail<3>() * s;
  if (w.norm() > 1e-12) D.linear() = Eigen::AngleAxisd(w.norm(), w.normalized()).toRotationMatrix();
  D.translation() = delta.head<3>() * s;
  return D;
}

Alignment Registration::align(const std::vector<Vec3>& edges, const std::vector<Vec3>& planes, const FeatureMap& map,
                              const Pose3& guess) const {
  std::vector<TimedPoint> e, p;
  e.reserve(edges.size());
  p.reserve(planes.size());
  for (const auto& x : edges) e.push_back({x, 1.0});
  for (const auto& x : planes) p.push_back({x, 1.0});
  Vec6 d;
  return align_motion(e, p, map, guess, Vec6::Zero(), &d);
}

Alignment Registration::align_motion(const std::vector<TimedPoint>& edges, const std::vector<TimedPoint>& planes,
                                     const FeatureMap& map, const Pose3& origin, const Vec6& predicted,
                                     Vec6* delta_out) const {
  Alignment out;
  Vec6 delta = predicted;
  const std::size_t k = std::size_t(std::clamp(cfg_.knn, 3, 20));
  std::size_t idx[20];
  double d2[20];
  const double max_d2 = cfg_.max_neighbour_dist * cfg_.max_neighbour_dist;
  Normal eq;
  Eigen::SelfAdjointEigenSolver<Matrix6d> es;
  Eigen::Matrix<double, 6, 1> S;
  S << 1, 1, 1, 1.0 / kLever, 1.0 / kLever, 1.0 / kLever;
  // Decoupling (LeGO-LOAM's two-step idea in one solve): on a race track the ground is most of the returns and its
  // locally fitted normals are noisy; let it constrain only what it can (z, roll, pitch), and the edges (cones,
  // posts) and the other planes (fences, stacks) only x, y and yaw.
  Vec6 all = Vec6::Ones(), planar, vertical;
  planar << 1, 1, 0, 0, 0, 1;
  vertical << 0, 0, 1, 1, 1, 0;
  if (!cfg_.decouple) planar = vertical = all;
  // The constant-velocity prediction as a prior, in the residuals' units: (σ_residual / σ_prior)².
  Vec6 prior_w;
  const double wt = std::pow(cfg_.residual_sigma / cfg_.prior_sigma_translation, 2),
               wr = std::pow(cfg_.residual_sigma / cfg_.prior_sigma_rotation, 2);
  prior_w << wt, wt, wt, wr, wr, wr;
  const Eigen::Matrix3d R0 = origin.linear();
  struct Match {
    bool valid = false;
    Vec3 mean, u1, u2;  // a line: the two directions across it; a plane: u1 its normal
  };
  std::vector<Match> edge_match, plane_match;
  for (int it = 0; it < cfg_.max_iterations; ++it) {
    eq = Normal{};
    out.edge_matches = out.plane_matches = 0;
    // One scalar residual r along the world direction `dir` of point x: q = origin · motion(δ, s) · p, so
    // ∂q/∂v = s·R0 and ∂q/∂ω ≈ −s·R(s) [p]× (first order in the rotation within the increment).
    auto add = [&](const TimedPoint& x, const Eigen::Matrix3d& Rs, const Vec3& dir, double r, double w,
                   const Vec6& mask) {
      Vec6 J;
      J << x.s * (R0.transpose() * dir), x.s * x.p.cross(Rs.transpose() * dir);
      J = J.cwiseProduct(mask);
      eq.H += w * J * J.transpose();
      eq.g += w * J * r;
      eq.wr2 += w * r * r;
      ++eq.n;
    };
    // Correspondences (the map line or plane of each point) are searched every `reassociate_every` iterations and
    // kept in between: the k-d tree searches and the 3×3 eigen-decompositions are most of the time.
    const bool reassociate = it % std::max(1, cfg_.reassociate_every) == 0;
    if (reassociate) {
      edge_match.assign(edges.size(), Match{});
      plane_match.assign(planes.size(), Match{});
    }
    if (!map.edges.empty()) {
      const auto& mp = map.edges.points();
      for (std::size_t i = 0; i < edges.size(); ++i) {
        const auto& x = edges[i];
        const Pose3 T = origin * motion(delta, x.s);
        const Vec3 q = T * x.p;
        Match& m = edge_match[i];
        if (reassociate) {
          if (map.edges.knn(q, k, idx, d2) < k || d2[k - 1] > max_d2) continue;
          const auto [mean, e3] = local_shape(mp, idx, k);
          // A line: one dominant direction (LOAM's test, largest eigenvalue 3× the middle one). Otherwise a small
          // blob (a cone: one ring per scan hits it, its silhouettes scatter round its axis): the vertical line
          // through the blob's centre, as long as the blob is narrow.
          if (e3.eigenvalues()[2] >= 3 * e3.eigenvalues()[1]) {
            m.u1 = e3.eigenvectors().col(0), m.u2 = e3.eigenvectors().col(1);
          } else if (e3.eigenvalues()[2] < cfg_.blob_radius * cfg_.blob_radius * double(k)) {
            m.u1 = Vec3::UnitX(), m.u2 = Vec3::UnitY();
          } else {
            continue;
          }
          m.mean = mean;
          m.valid = true;
        }
        if (!m.valid) continue;
        const Vec3 dq = q - m.mean;
        const double r1 = m.u1.dot(dq), r2 = m.u2.dot(dq);
        const double w = huber(std::hypot(r1, r2), cfg_.huber_delta);
        const Eigen::Matrix3d Rs = T.linear();
        add(x, Rs, m.u1, r1, w, planar);
        add(x, Rs, m.u2, r2, w, planar);
        ++out.edge_matches;
      }
    }
    if (!map.planes.empty()) {
      const auto& mp = map.planes.points();
      for (std::size_t i = 0; i < planes.size(); ++i) {
        const auto& x = planes[i];
        const Pose3 T = origin * motion(delta, x.s);
        const Vec3 q = T * x.p;
        Match& m = plane_match[i];
        if (reassociate) {
          if (map.planes.knn(q, k, idx, d2) < k || d2[k - 1] > max_d2) continue;
          const auto [mean, e3] = local_shape(mp, idx, k);
          const auto& ev = e3.eigenvalues();
          // A plane: thin across, spread along two directions (points all on one ring define no plane).
          if (ev[0] > 0.1 * ev[1] || ev[1] < 1e-3 * k) continue;
          m.mean = mean;
          m.u1 = e3.eigenvectors().col(0);
          m.valid = true;
        }
        if (!m.valid) continue;
        const double r = m.u1.dot(q - m.mean);
        const Eigen::Matrix3d Rs = T.linear();
        const bool ground = std::abs((Rs.transpose() * m.u1).z()) >= cfg_.ground_normal_z;
        add(x, Rs, m.u1, r, huber(r, cfg_.huber_delta), ground ? vertical : planar);
        ++out.plane_matches;
      }
    }
    out.iterations = it + 1;
    if (eq.n < 6) break;
    // Gauss–Newton with the prior: the prior holds directions the scene leaves free at the prediction, instead of
    // a hard remapping that keeps a prediction exactly (and feeds a wrong one back into the next scan).
    const Matrix6d H = eq.H + Matrix6d(prior_w.asDiagonal());
    const Vec6 g = eq.g + prior_w.cwiseProduct(delta - predicted);
    const Vec6 d = -H.ldlt().solve(g);
    delta += d;
    if (d.head<3>().norm() < cfg_.converged_step && d.tail<3>().norm() < cfg_.converged_step) break;
  }
  out.pose = origin * motion(delta, 1.0);
  *delta_out = delta;
  if (eq.n < 6) {
    out.degenerate = true;
    out.degenerate_directions = 6;
    out.information_eigen.setZero();
    out.covariance = Matrix6d::Identity() * cfg_.degenerate_sigma * cfg_.degenerate_sigma;
    return out;
  }
  const Matrix6d Hs = S.asDiagonal() * eq.H * S.asDiagonal();
  es.compute(Hs);
  out.information_eigen = es.eigenvalues();
  // σ² of one residual from the fit itself, floored: the covariance must not claim better than the sensor.
  const double s2 = std::max(eq.wr2 / std::max(1, eq.n - 6), 1e-4);
  out.rms = std::sqrt(eq.wr2 / eq.n);
  Matrix6d cov_s = Matrix6d::Zero();
  const double big = cfg_.degenerate_sigma * cfg_.degenerate_sigma;
  for (int i = 0; i < 6; ++i) {
    const double l = es.eigenvalues()[i];
    const Vec6 v = es.eigenvectors().col(i);
    const bool deg = l < cfg_.min_information;
    out.degenerate_directions += deg;
    // In scaled units a degenerate rotation's σ would be kLever× the configured one: take the larger, honestly.
    cov_s += v * v.transpose() * (deg ? big * kLever * kLever : s2 / l);
  }
  out.degenerate = out.degenerate_directions > 0;
  out.covariance = S.asDiagonal() * cov_s * S.asDiagonal();
  return out;
}

}  // namespace fsd::lidar_odometry
