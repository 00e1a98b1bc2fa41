#include "localization/lidar_odometry/config.hpp"

namespace fsd::lidar_odometry {

const ConfigSection<FeatureConfig>& feature_section() {
  using C = FeatureConfig;
  static const auto s =
      ConfigSection<C>("localization.lidar_odometry.features")
          .integer("neighbours", &C::neighbours, 2, 20, "",
                   "Ring neighbours each side of a point in its smoothness c (LOAM eq. 5).")
          .integer("sectors", &C::sectors, 1, 64, "", "Azimuth sectors per ring; features are picked per sector.")
          .integer("edges_per_sector", &C::edges_per_sector, 0, 100, "", "Sharpest points kept per sector ...")
          .number("edge_threshold", &C::edge_threshold, 0.0, 10.0, "", "... with a smoothness c above this.")
          .integer("planes_per_sector", &C::planes_per_sector, 0, 1000, "", "Flattest points kept per sector ...")
          .number("plane_threshold", &C::plane_threshold, 0.0, 10.0, "", "... with a smoothness c below this.")
          .number("min_range", &C::min_range, 0.0, 10.0, "m", "Closer returns are ignored (the car itself).")
          .number("max_range", &C::max_range, 1.0, 200.0, "m", "Farther returns are ignored (too sparse to match).")
          .number("occlusion_gap", &C::occlusion_gap, 0.01, 1.0, "",
                  "Relative range jump between ring neighbours that marks the far side as occluded.")
          .number("parallel_beam_ratio", &C::parallel_beam_ratio, 0.001, 1.0, "",
                  "A point whose both ring neighbours lie farther than this share of its range is grazing: ignored.");
  return s;
}

const ConfigSection<OdometryConfig>& odometry_section() {
  using C = OdometryConfig;
  static const auto s =
      ConfigSection<C>("localization.lidar_odometry")
          .integer("max_iterations", &C::max_iterations, 1, 100, "", "Gauss-Newton iterations per scan.")
          .integer("reassociate_every", &C::reassociate_every, 1, 100, "",
                   "Gauss-Newton iterations between searches of the map neighbours; kept in between.")
          .number("converged_step", &C::converged_step, 1e-8, 1.0, "m|rad",
                  "An update smaller than this ends the iterations.")
          .integer("knn", &C::knn, 3, 20, "", "Map neighbours that define a line (edges) or a plane (planes).")
          .number("max_neighbour_dist", &C::max_neighbour_dist, 0.05, 10.0, "m",
                  "Neighbours farther than this define nothing.")
          .number("huber_delta", &C::huber_delta, 0.001, 10.0, "m", "Corner of the Huber kernel on the residuals.")
          .number("blob_radius", &C::blob_radius, 0.0, 2.0, "m",
                  "Edge neighbours not on a line but spread less than this: matched to a vertical line (a cone).")
          .number("min_information", &C::min_information, 0.0, 1e6, "",
                  "Eigenvalue of the normal matrix (rotations scaled by 10 m) below which the scene is degenerate.")
          .number("degenerate_sigma", &C::degenerate_sigma, 0.01, 1e3, "m|rad",
                  "Standard deviation reported along a degenerate direction.")
          .boolean("vehicle_motion", &C::vehicle_motion,
                   "The daemon's LiDAR odometry deskews and predicts each scan with the car's measured motion (rear "
                   "wheel speed, the GNSS-INS yaw rate) instead of the scans' own low-passed increments.")
          .boolean("hold_degenerate", &C::hold_degenerate,
                   "A scan whose matches leave a direction free keeps the constant-velocity prediction as its pose.")
          .integer("deskew_passes", &C::deskew_passes, 1, 5, "",
                   "Registrations per scan; each after the first deskews with the motion the previous one found. "
                   "With the car's measured motion (vehicle_motion) one: that motion is the scan's own.")
          .number("velocity_gain", &C::velocity_gain, 0.05, 1.0, "",
                  "Share of the newest increment in the twist that deskews and predicts the next scan (a low-pass: "
                  "a wrong increment is not fed back whole into the next scan's deskew).")
          .boolean("decouple", &C::decouple,
                   "Ground planes constrain only z, roll and pitch; edges and other planes only x, y and yaw.")
          .number("ground_normal_z", &C::ground_normal_z, 0.0, 1.0, "",
                  "A plane match whose normal has at least this z component (body frame) is ground.")
          .number("residual_sigma", &C::residual_sigma, 1e-4, 1.0, "m",
                  "Standard deviation of one matched residual: weighs the motion prior against the matches.")
          .number("prior_sigma_translation", &C::prior_sigma_translation, 1e-4, 100.0, "m",
                  "Standard deviation of the constant-velocity prediction per scan, translation ...")
          .number("prior_sigma_rotation", &C::prior_sigma_rotation, 1e-5, 10.0, "rad", "... and rotation.")
          .integer("keyframes", &C::keyframes, 1, 50, "", "Keyframes in the local map.")
          .number("keyframe_distance", &C::keyframe_distance, 0.0, 100.0, "m",
                  "Distance travelled since the last keyframe that makes a new one ...")
          .number("keyframe_angle", &C::keyframe_angle, 0.0, 3.2, "rad", "... or the angle turned.")
          .number("map_voxel", &C::map_voxel, 0.01, 2.0, "m",
                  "The local map keeps one feature per voxel of this size.");
  return s;
}

void describe_lidar_odometry_config(ConfigSchema& schema) {
  feature_section().describe(schema);
  odometry_section().describe(schema);
}

LidarOdometryConfig read_lidar_odometry_config(const Config& cfg) {
  return {feature_section().read(cfg), odometry_section().read(cfg)};
}

}  // namespace fsd::lidar_odometry
