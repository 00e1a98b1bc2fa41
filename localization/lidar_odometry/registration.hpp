#pragma once
// Scan-to-map registration (LOAM §VI): each edge point pulled onto the line of its nearest map edges, each plane
// point onto the plane of its nearest map planes, Gauss–Newton with a Huber kernel over the 6-DoF body pose.
// Degeneracy (Zhang, Kaess & Singh 2016): directions of the normal matrix with too little information are not
// updated (the prediction stands there) and get a large σ in the covariance instead of an invented value.
#include <vector>

#include "localization/lidar_odometry/config.hpp"
#include "localization/lidar_odometry/feature_map.hpp"

namespace fsd::lidar_odometry {

using Matrix6d = Eigen::Matrix<double, 6, 6>;

struct Alignment {
  Pose3 pose = Pose3::Identity();                 // odometry frame ← body
  Matrix6d covariance = Matrix6d::Identity();     // over the body-frame perturbation (x, y, z, roll, pitch, yaw)
  Eigen::Matrix<double, 6, 1> information_eigen;  // eigenvalues of the scaled normal matrix, ascending
  bool degenerate = false;
  int degenerate_directions = 0;
  int iterations = 0;
  int edge_matches = 0, plane_matches = 0;
  double rms = 0;  // m, of the matched residuals at the end
};

using Vec6 = Eigen::Matrix<double, 6, 1>;

// The body's motion over a fraction s of an increment δ = (v, ω) (translation, rotation vector) at constant twist,
// first order: rotation s·ω and translation s·v independently (δ over s = 1 is the increment itself).
Pose3 motion(const Vec6& delta, double s);

// A body-frame point not yet deskewed, with its firing time as the fraction s of the increment: 0 at the previous
// scan's pose, 1 at this scan's (its last firing).
struct TimedPoint {
  Vec3 p = Vec3::Zero();
  double s = 1;
};

class Registration {
 public:
  explicit Registration(const OdometryConfig& cfg = {}) : cfg_(cfg) {}
  // Rigid: edges / planes are body-frame points all taken at the pose sought; `guess`: the prediction of the pose.
  Alignment align(const std::vector<Vec3>& edges, const std::vector<Vec3>& planes, const FeatureMap& map,
                  const Pose3& guess) const;
  // With the deskew inside the fit: the pose of each point is origin · motion(δ, s), the increment δ solved for
  // (from `predicted`, also the constant-velocity prior), so the motion a scan is deskewed with is the motion it is
  // registered with (no feedback of one scan's error into the next one's deskew). Alignment::pose = origin ·
  // motion(δ, 1); `delta` returns δ.
  Alignment align_motion(const std::vector<TimedPoint>& edges, const std::vector<TimedPoint>& planes,
                         const FeatureMap& map, const Pose3& origin, const Vec6& predicted, Vec6* delta) const;

 private:
  OdometryConfig cfg_;
};

}  // namespace fsd::lidar_odometry
