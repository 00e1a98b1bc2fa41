#pragma once
// The LiDAR odometry's configuration: localization.lidar_odometry.features (LOAM's feature selection) and
// localization.lidar_odometry (matching, robust kernel, degeneracy, local map).
#include "common/config.hpp"

namespace fsd::lidar_odometry {

struct FeatureConfig {
  int neighbours = 5;                 // points each side of a point in its ring for the smoothness c (eq. 5)
  int sectors = 6;                    // each ring is split into this many azimuth sectors, features picked per sector
  int edges_per_sector = 10;          // sharpest points kept per sector ...
  double edge_threshold = 0.1;        // ... with c above this
  int planes_per_sector = 8;          // flattest points kept per sector ...
  double plane_threshold = 0.05;      // ... with c below this
  double min_range = 1.0;             // m: closer returns are the car itself
  double max_range = 60.0;            // m: farther returns are too sparse to match
  double occlusion_gap = 0.1;         // relative range jump between ring neighbours that marks an occlusion
  double parallel_beam_ratio = 0.02;  // a point whose neighbours lie farther than this share of its range: grazing
};
const ConfigSection<FeatureConfig>& feature_section();

struct OdometryConfig {
  int max_iterations = 12;          // Gauss–Newton iterations per scan
  int reassociate_every = 3;        // iterations between searches of the map neighbours (kept in between)
  double converged_step = 1e-4;     // m or rad: an update smaller than this ends the iterations
  int knn = 5;                      // neighbours that define a line or a plane
  double max_neighbour_dist = 1.0;  // m: farther neighbours define nothing
  double huber_delta = 0.1;         // m: the robust kernel's corner
  double blob_radius = 0.2;         // m: edge neighbours not on a line but within this spread: a vertical post
  double min_information = 1.0;     // eigenvalue of the normal matrix (rotation per 10 m) below which: degenerate
  double degenerate_sigma = 10.0;   // m or rad: the σ reported along a degenerate direction
  bool vehicle_motion = true;       // the daemon hands the odometry the wheel speed and yaw rate (deskew, prediction)
  bool hold_degenerate = true;      // a degenerate scan keeps the constant-velocity prediction as its pose
  int deskew_passes = 2;            // registrations per scan, each deskewed with the motion the previous one found
                                    // (one with a measured twist: that is the scan's motion)
  double velocity_gain = 0.2;    // share of the newest increment in the twist that deskews and predicts the next scan
  bool decouple = true;          // ground planes constrain only z, roll, pitch; edges and other planes x, y, yaw
  double ground_normal_z = 0.9;  // a plane match whose normal is this close to the body's z is ground
  double residual_sigma = 0.03;  // m: σ of one matched residual, scales the motion prior against the matches
  double prior_sigma_translation = 0.1;  // m: constant-velocity prediction's σ per scan (translation) ...
  double prior_sigma_rotation = 0.02;    // rad: ... and rotation
  int keyframes = 10;                    // keyframes of the local map
  double keyframe_distance = 2.0;        // m travelled ...
  double keyframe_angle = 0.17;          // ... or rad turned since the last keyframe makes a new one
  double map_voxel = 0.15;               // m: one map feature per voxel
};
const ConfigSection<OdometryConfig>& odometry_section();

struct LidarOdometryConfig {
  FeatureConfig features;
  OdometryConfig odometry;
};
void describe_lidar_odometry_config(ConfigSchema& schema);
LidarOdometryConfig read_lidar_odometry_config(const Config& cfg);

}  // namespace fsd::lidar_odometry
