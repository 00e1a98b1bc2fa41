#pragma once
// A cone candidate of the LiDAR stages: one cluster that passed the size filter, with what the camera stage needs to
// project it into the image (position, envelope, size) and what the LiDAR alone could tell about it. The LiDAR
// detector reports candidates and ConeDetections one to one, in the same order (LidarDetection::candidates[i] is
// LidarDetection::detections.cones[i]), so a later stage can verify or reject cone i and recolour it.
//
// Frame: the detector's output frame, i.e. the vehicle frame (x forward, y left, z up, origin at the rear-axle
// centre on the ground) in the daemon, the input cloud's own frame in `fsd detect`.
#include <cstdint>
#include <vector>

#include "common/geometry.hpp"
#include "common/types.hpp"

namespace fsd {

struct ConeCandidate {
  Vec3 centroid = Vec3::Zero();  // mean of the cluster's points
  Vec3 min = Vec3::Zero();       // axis-aligned envelope of the cluster's points
  Vec3 max = Vec3::Zero();
  Vec3 position = Vec3::Zero();  // estimated centre of the cone's base, on the ground plane (the detection's position)
  std::uint32_t points = 0;      // points in the cluster (all accumulated frames)
  std::uint32_t rings = 0;       // distinct laser rings among them
  double range = 0;              // horizontal distance from the sensor to `position`, m
  double height = 0;             // top of the cluster above the ground plane, m
  double bottom = 0;             // lowest point of the cluster above the ground plane, m
  double width = 0;              // largest horizontal extent of the cluster, m
  float mean_intensity = 0;      // mean calibrated reflectivity of the points, 0..255
  bool big = false;              // taller than a small cone can look: a big (timing) cone
  std::vector<Point> cloud;      // the cluster's points (x, y, z in the frame above; ring, intensity, time kept)
};

}  // namespace fsd
