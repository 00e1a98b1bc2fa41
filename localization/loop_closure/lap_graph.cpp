#include "localization/loop_closure/lap_graph.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include <ceres/ceres.h>

namespace fsd::loop_closure {

namespace {

template <class T>
T wrap(const T& a) {
  using std::atan2, std::cos, std::sin;
  return atan2(sin(a), cos(a));
}

// The estimator's motion from keyframe i to i+1 (in i's frame), weighted by its σ.
struct OdometryLink {
  Pose2 z;
  double st, sy;
  template <class T>
  bool operator()(const T* a, const T* b, T* r) const {
    using std::cos, std::sin;
    const T dx = b[0] - a[0], dy = b[1] - a[1];
    const T c = cos(a[2]), s = sin(a[2]);
    r[0] = (c * dx + s * dy - T(z.x)) / T(st);
    r[1] = (-s * dx + c * dy - T(z.y)) / T(st);
    r[2] = wrap(b[2] - a[2] - T(z.yaw)) / T(sy);
    return true;
  }
};

// A cone seen from a keyframe: where the landmark is in the keyframe's vehicle frame against what was seen.
struct ConeSighting {
  Vec2 z;
  double sigma;
  template <class T>
  bool operator()(const T* pose, const T* cone, T* r) const {
    using std::cos, std::sin;
    const T dx = cone[0] - pose[0], dy = cone[1] - pose[1];
    const T c = cos(pose[2]), s = sin(pose[2]);
    r[0] = (c * dx + s * dy - T(z.x())) / T(sigma);
    r[1] = (-s * dx + c * dy - T(z.y())) / T(sigma);
    return true;
  }
};

}  // namespace

int LapGraph::add_keyframe(Stamp t, const Pose2& estimate) {
  keyframes_.push_back({t, estimate});
  return int(keyframes_.size()) - 1;
}

void LapGraph::observe(int k, int landmark, const Vec2& in_vehicle, double sigma) {
  if (k < 0 || k >= int(keyframes_.size()) || !in_vehicle.allFinite() || !(sigma > 0)) return;
  observations_.push_back({k, landmark, in_vehicle, sigma});
  parent_.try_emplace(landmark, landmark);
}

int LapGraph::root(int landmark) const {
  auto it = parent_.find(landmark);
  while (it != parent_.end() && it->second != it->first) it = parent_.find(it->second);
  return it == parent_.end() ? landmark : it->first;
}

void LapGraph::same_cone(int a, int b) {
  parent_.try_emplace(a, a);
  parent_.try_emplace(b, b);
  const int ra = root(a), rb = root(b);
  if (ra != rb) parent_[std::max(ra, rb)] = std::min(ra, rb);
}

LapGraphResult LapGraph::optimise() const {
  LapGraphResult out;
  for (const auto& k : keyframes_) out.poses.push_back(k.estimate);
  // Landmarks start where their first sighting puts them (the estimator's map).
  std::map<int, std::array<double, 2>> cones;
  for (const auto& o : observations_) {
    const int r = root(o.landmark);
    if (cones.count(r)) continue;
    const Vec2 p = keyframes_[std::size_t(o.k)].estimate.transform(o.in_vehicle);
    cones[r] = {p.x(), p.y()};
  }
  auto report = [&] {
    for (const auto& [id, _] : parent_) {
      const auto it = cones.find(root(id));
      if (it != cones.end()) out.landmarks[id] = Vec2(it->second[0], it->second[1]);
    }
  };
  if (keyframes_.size() < 2) {
    report();
    return out;
  }

  std::vector<std::array<double, 3>> x;
  for (const auto& k : keyframes_) x.push_back({k.estimate.x, k.estimate.y, k.estimate.yaw});
  ceres::Problem::Options po;
  po.loss_function_ownership = ceres::TAKE_OWNERSHIP;
  ceres::Problem problem(po);
  for (std::size_t i = 0; i + 1 < keyframes_.size(); ++i) {
    const Pose2& a = keyframes_[i].estimate;
    const Pose2& b = keyframes_[i + 1].estimate;
    const Pose2 z = a.inverse() * b;
    const double d = std::hypot(z.x, z.y);
    const double st = std::max(cfg_.translation_sigma_min, cfg_.translation_sigma_per_m * d);
    const double sy = std::max(cfg_.yaw_sigma_min, cfg_.yaw_sigma_per_m * d);
    problem.AddResidualBlock(new ceres::AutoDiffCostFunction<OdometryLink, 3, 3, 3>(new OdometryLink{z, st, sy}),
                             nullptr, x[i].data(), x[i + 1].data());
  }
  for (const auto& o : observations_) {
    auto& cone = cones[root(o.landmark)];
    // The Huber corner in σ units: a residual is whitened by the sighting's σ.
    auto* loss = new ceres::HuberLoss(cfg_.observation_huber / o.sigma);
    problem.AddResidualBlock(
        new ceres::AutoDiffCostFunction<ConeSighting, 2, 3, 2>(new ConeSighting{o.in_vehicle, o.sigma}), loss,
        x[std::size_t(o.k)].data(), cone.data());
  }
  problem.SetParameterBlockConstant(x[0].data());

  ceres::Solver::Options so;
  so.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  so.max_num_iterations = cfg_.max_iterations;
  so.num_threads = 1;  // the core owns no thread
  so.logging_type = ceres::SILENT;
  const auto initial_cones = cones;
  ceres::Solver::Summary summary;
  ceres::Solve(so, &problem, &summary);
  out.solved = summary.IsSolutionUsable();
  out.cost_before = summary.initial_cost;
  out.cost_after = summary.final_cost;
  out.iterations = int(summary.iterations.size());
  if (out.solved)
    for (std::size_t i = 0; i < x.size(); ++i) out.poses[i] = Pose2{x[i][0], x[i][1], wrap_angle(x[i][2])};
  else
    cones = initial_cones;
  report();
  return out;
}

}  // namespace fsd::loop_closure
