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

class Registration {
 public:
  explicit Registration(const OdometryConfig& cfg = {}) : cfg_(cfg) {}
  // edges / planes: body-frame points (deskewed); `guess`: the prediction of the pose.
  Alignment align(const std::vector<Vec3>& edges, const std::vector<Vec3>& planes, const FeatureMap& map,
                  const Pose3& guess) const;

 private:
  OdometryConfig cfg_;
};

}  // namespace fsd::lidar_odometry
