#pragma once
// The target of the matching: edge and plane points in the odometry frame with their k-d trees (nanoflann).
#include <memory>
#include <vector>

#include "common/geometry.hpp"

namespace fsd::lidar_odometry {

// A k-d tree over a point set it owns.
class PointIndex {
 public:
  PointIndex();
  ~PointIndex();
  PointIndex(PointIndex&&) noexcept;
  PointIndex& operator=(PointIndex&&) noexcept;
  void build(std::vector<Vec3> points);
  // The k nearest points' indices and squared distances, nearest first; fewer when the set is smaller.
  std::size_t knn(const Vec3& q, std::size_t k, std::size_t* idx, double* d2) const;
  const std::vector<Vec3>& points() const;
  bool empty() const { return !tree_; }

 private:
  struct Tree;  // owns the points on the heap: the tree's adaptor points at them, moves keep them in place
  std::unique_ptr<Tree> tree_;
};

struct FeatureMap {
  PointIndex edges, planes;
};

// One point per voxel (the first one seen): keeps the local map's density even where keyframes overlap.
std::vector<Vec3> voxel_downsample(const std::vector<Vec3>& pts, double voxel);

}  // namespace fsd::lidar_odometry
