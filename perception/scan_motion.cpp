#include "perception/scan_motion.hpp"

#include <algorithm>

namespace fsd {

BodyPoseAt interpolate_poses(Stamp t0, const Pose3& pose0, Stamp t1, const Pose3& pose1) {
  const Eigen::Quaterniond q0(pose0.linear()), q1(pose1.linear());
  const Vec3 p0 = pose0.translation(), p1 = pose1.translation();
  return [=](Stamp t) {
    const double s = t1 > t0 ? std::clamp((t - t0) / (t1 - t0), 0.0, 1.0) : 0.0;
    Pose3 T = Pose3::Identity();
    T.linear() = q0.slerp(s, q1).toRotationMatrix();
    T.translation() = p0 + s * (p1 - p0);
    return T;
  };
}

ScanMotion::ScanMotion(const Pose3& body_from_sensor, Stamp t_first, Stamp t_last, Stamp t_ref,
                       const BodyPoseAt& pose_at, int knots)
    : t_first_(t_first) {
  const auto knot_of = [](const Pose3& M) {
    Knot k;
    k.R = M.linear().cast<float>();
    k.t = M.translation().cast<float>();
    k.w.setZero();
    k.v.setZero();
    return k;
  };
  if (!pose_at || !(t_last > t_first) || knots < 1) {
    if (pose_at) reference_pose_ = pose_at(t_ref);
    has_motion_ = static_cast<bool>(pose_at);
    knots_.push_back(knot_of(body_from_sensor));
    return;
  }
  has_motion_ = true;
  reference_pose_ = pose_at(t_ref);
  const Pose3 ref_inv = reference_pose_.inverse();
  std::vector<Pose3> M;  // body(t_ref) ← sensor(τ_k)
  M.reserve(static_cast<std::size_t>(knots) + 1);
  const double dt = (t_last - t_first) / knots;
  for (int k = 0; k <= knots; ++k) M.push_back(ref_inv * pose_at(t_first + k * dt) * body_from_sensor);
  for (std::size_t k = 0; k < M.size(); ++k) {
    Knot K = knot_of(M[k]);
    if (k + 1 < M.size()) {
      const Pose3 d = M[k].inverse() * M[k + 1];  // sensor(τ_k) ← sensor(τ_k+1)
      const Eigen::AngleAxisd aa(d.linear());
      K.w = (aa.angle() * aa.axis()).cast<float>();
      K.v = d.translation().cast<float>();
    }
    knots_.push_back(K);
  }
  inv_dt_ = 1.0 / dt;
  last_ = static_cast<double>(knots);
}

}  // namespace fsd
