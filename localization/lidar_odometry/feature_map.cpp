#include "localization/lidar_odometry/feature_map.hpp"

#include <cmath>
#include <cstdint>
#include <unordered_set>

#include <nanoflann.hpp>

namespace fsd::lidar_odometry {

namespace {
struct Cloud {
  const std::vector<Vec3>* pts;
  std::size_t kdtree_get_point_count() const { return pts->size(); }
  double kdtree_get_pt(std::size_t i, std::size_t d) const { return (*pts)[i][int(d)]; }
  template <class B>
  bool kdtree_get_bbox(B&) const {
    return false;
  }
};
using Tree3 = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, Cloud>, Cloud, 3, std::size_t>;
}  // namespace

struct PointIndex::Tree {
  std::vector<Vec3> pts;
  Cloud cloud;
  Tree3 tree;
  explicit Tree(std::vector<Vec3> p)
      : pts(std::move(p)), cloud{&pts}, tree(3, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(20)) {
    tree.buildIndex();
  }
};

PointIndex::PointIndex() = default;
PointIndex::~PointIndex() = default;
PointIndex::PointIndex(PointIndex&&) noexcept = default;
PointIndex& PointIndex::operator=(PointIndex&&) noexcept = default;

void PointIndex::build(std::vector<Vec3> points) {
  tree_.reset();
  if (!points.empty()) tree_ = std::make_unique<Tree>(std::move(points));
}

const std::vector<Vec3>& PointIndex::points() const {
  static const std::vector<Vec3> none;
  return tree_ ? tree_->pts : none;
}

std::size_t PointIndex::knn(const Vec3& q, std::size_t k, std::size_t* idx, double* d2) const {
  if (!tree_) return 0;
  return tree_->tree.knnSearch(q.data(), k, idx, d2);
}

std::vector<Vec3> voxel_downsample(const std::vector<Vec3>& pts, double voxel) {
  std::unordered_set<std::uint64_t> seen;
  std::vector<Vec3> out;
  out.reserve(pts.size());
  for (const auto& p : pts) {
    // 21 bits per axis: ±1e5 voxels around the origin, far beyond a track.
    auto key = [&](int a) { return std::uint64_t(std::int64_t(std::floor(p[a] / voxel)) & 0x1FFFFF); };
    if (seen.insert(key(0) | key(1) << 21 | key(2) << 42).second) out.push_back(p);
  }
  return out;
}

}  // namespace fsd::lidar_odometry
