#pragma once
// Motion compensation of one LiDAR scan (deskew). A spinning sensor fires its points over the ~100 ms of a
// revolution while the car moves; each point is in the sensor frame of its own firing time. ScanMotion maps every
// point into the body frame at one reference time, from the body poses the caller gives (truth, odometry or the
// fused estimate: any odometry/map ← body pose as a function of time).
//
// The pose function is sampled at `knots` + 1 evenly spaced times over the scan (never per point: a std::function
// call per point would cost more than the rest of the stage); between two knots the motion is interpolated to
// first order in the small relative rotation (error below 0.1 mm for a 1 rad/s yaw rate and 10 knots per 100 ms).
#include <functional>
#include <vector>

#include <Eigen/Core>

#include "common/geometry.hpp"
#include "common/time.hpp"

namespace fsd {

// Body pose in the odometry (or map) frame at a time: odom ← body.
using BodyPoseAt = std::function<Pose3(Stamp)>;

// The body pose interpolated between two stamped poses (translation linearly, rotation by slerp), held constant
// outside [t0, t1]: what a caller with only the poses at the scan's first and last firing passes.
BodyPoseAt interpolate_poses(Stamp t0, const Pose3& pose0, Stamp t1, const Pose3& pose1);

class ScanMotion {
 public:
  // Points fired over [t_first, t_last], given in the sensor frame, mapped into the body frame at t_ref.
  // Without a pose function every point gets body ← sensor only (a standing car, or a single cloud).
  ScanMotion(const Pose3& body_from_sensor, Stamp t_first, Stamp t_last, Stamp t_ref, const BodyPoseAt& pose_at,
             int knots);

  // A sensor-frame point fired at t, in the body frame at t_ref.
  Eigen::Vector3f to_reference(const Eigen::Vector3f& p, Stamp t) const {
    if (knots_.size() == 1) return knots_[0].R * p + knots_[0].t;
    double s = (t - t_first_) * inv_dt_;
    s = s < 0 ? 0 : (s > last_ ? last_ : s);
    auto k = static_cast<std::size_t>(s);
    if (k >= knots_.size() - 1) k = knots_.size() - 2;
    const auto& K = knots_[k];
    const float u = static_cast<float>(s - static_cast<double>(k));
    return K.R * (p + u * (K.w.cross(p) + K.v)) + K.t;
  }

  // odom ← body at t_ref (identity without a pose function).
  const Pose3& reference_pose() const { return reference_pose_; }
  bool has_motion() const { return has_motion_; }

 private:
  struct Knot {
    Eigen::Matrix3f R;  // body(t_ref) ← sensor(τ_k)
    Eigen::Vector3f t;
    Eigen::Vector3f w;  // rotation vector of sensor(τ_k) ← sensor(τ_k+1)
    Eigen::Vector3f v;  // its translation
  };
  std::vector<Knot> knots_;
  Stamp t_first_ = 0;
  double inv_dt_ = 0, last_ = 0;
  Pose3 reference_pose_ = Pose3::Identity();
  bool has_motion_ = false;
};

}  // namespace fsd
