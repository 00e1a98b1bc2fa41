#include "perception/clusterer.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/search/kdtree.h>
#include <pcl/segmentation/extract_clusters.h>

namespace fsd {

const ConfigSection<ClusterConfig>& cluster_section() {
  static const auto s =
      ConfigSection<ClusterConfig>("perception.lidar.cluster")
          .string("method", &ClusterConfig::method, {"grid", "pcl_euclidean"},
                  "Clustering: grid = hash grid + union-find with a range-aware tolerance; pcl_euclidean = the "
                  "paper's PCL EuclideanClusterExtraction (fixed tolerance).")
          .number("tolerance", &ClusterConfig::tolerance, 0.02, 2.0, "m",
                  "Points nearer than this (in the ground plane, see z_weight) are one object.")
          .number("range_factor", &ClusterConfig::range_factor, 0.0, 0.1, "m/m",
                  "grid: the tolerance grows to this times the range from the sensor when that is larger.")
          .number("z_weight", &ClusterConfig::z_weight, 0.0, 1.0, "",
                  "Weight of the height difference in the clustering distance (0 = footprint only).")
          .integer("min_points", &ClusterConfig::min_points, 1, 100000, "", "Smaller clusters are dropped.")
          .integer("max_points", &ClusterConfig::max_points, 1, 10000000, "",
                   "Larger clusters are dropped (walls, fences, cars).");
  return s;
}

namespace {

std::uint32_t find_root(std::vector<std::uint32_t>& parent, std::uint32_t i) {
  while (parent[i] != i) {
    parent[i] = parent[parent[i]];
    i = parent[i];
  }
  return i;
}

}  // namespace

std::vector<Cluster> Clusterer::cluster(const std::vector<Point>& points, const Vec2& sensor_xy,
                                        std::size_t* too_large) {
  std::vector<Cluster> all = cfg_.method == "pcl_euclidean" ? cluster_pcl(points) : cluster_grid(points, sensor_xy);
  std::vector<Cluster> out;
  out.reserve(all.size());
  std::size_t large = 0;
  for (auto& c : all) {
    if (c.indices.size() < static_cast<std::size_t>(cfg_.min_points)) continue;
    if (c.indices.size() > static_cast<std::size_t>(cfg_.max_points)) {
      ++large;
      continue;
    }
    out.push_back(std::move(c));
  }
  if (too_large) *too_large = large;
  return out;
}

std::vector<Cluster> Clusterer::cluster_grid(const std::vector<Point>& points, const Vec2& sensor_xy) {
  const auto n = static_cast<std::uint32_t>(points.size());
  if (n == 0) return {};
  float x0 = std::numeric_limits<float>::max(), y0 = x0, x1 = -x0, y1 = -x0;
  tol_.resize(n);
  float max_tol = 0;
  for (std::uint32_t i = 0; i < n; ++i) {
    const auto& q = points[i];
    x0 = std::min(x0, q.x), x1 = std::max(x1, q.x);
    y0 = std::min(y0, q.y), y1 = std::max(y1, q.y);
    const double r = std::hypot(q.x - sensor_xy.x(), q.y - sensor_xy.y());
    tol_[i] = static_cast<float>(std::max(cfg_.tolerance, cfg_.range_factor * r));
    max_tol = std::max(max_tol, tol_[i]);
  }
  // Cells with a diagonal of the base tolerance: the points of one cell are all within tolerance of each other, so
  // a cell is joined at once and two cells need only one close pair. (A huge extent gets coarser cells, whose
  // points are then checked pair by pair.)
  double cell = cfg_.tolerance / std::sqrt(2.0);
  while ((x1 - x0) / cell * (y1 - y0) / cell > 4.0e6) cell *= 2;
  const bool cell_is_connected = cell * std::sqrt(2.0) <= cfg_.tolerance * (1.0 + 1e-9);
  const auto reach = static_cast<std::int64_t>(std::ceil(max_tol / cell));
  const auto nx = static_cast<std::int64_t>((x1 - x0) / cell) + 1, ny = static_cast<std::int64_t>((y1 - y0) / cell) + 1;
  const float inv = static_cast<float>(1.0 / cell);
  // Counting sort of the points by cell.
  cell_of_.resize(n);
  cell_start_.assign(static_cast<std::size_t>(nx * ny) + 1, 0);
  for (std::uint32_t i = 0; i < n; ++i) {
    const auto cx = std::min(nx - 1, static_cast<std::int64_t>((points[i].x - x0) * inv));
    const auto cy = std::min(ny - 1, static_cast<std::int64_t>((points[i].y - y0) * inv));
    cell_of_[i] = static_cast<std::uint32_t>(cy * nx + cx);
    ++cell_start_[cell_of_[i] + 1];
  }
  std::partial_sum(cell_start_.begin(), cell_start_.end(), cell_start_.begin());
  order_.resize(n);
  {
    std::vector<std::uint32_t> fill(cell_start_.begin(), cell_start_.end() - 1);
    for (std::uint32_t i = 0; i < n; ++i) order_[fill[cell_of_[i]]++] = i;
  }
  parent_.resize(n);
  std::iota(parent_.begin(), parent_.end(), 0u);
  const float zw = static_cast<float>(cfg_.z_weight);
  const auto close = [&](std::uint32_t i, std::uint32_t j) {
    const auto& p = points[i];
    const auto& q = points[j];
    const float dx = p.x - q.x, dy = p.y - q.y, dz = zw * (p.z - q.z);
    const float tol = std::max(tol_[i], tol_[j]);
    return dx * dx + dy * dy + dz * dz <= tol * tol;
  };
  // Footprint distance and cells a tolerance across the diagonal: a cell is one object, and two cells need one
  // close pair. With a height term, or coarse cells, every pair is checked.
  const bool fast = cell_is_connected && zw == 0.0f;
  const auto join = [&](std::uint32_t i, std::uint32_t j) {
    const std::uint32_t ri = find_root(parent_, i), rj = find_root(parent_, j);
    if (ri != rj) parent_[std::max(ri, rj)] = std::min(ri, rj);
  };
  // Joins two cells' points; with `fast`, one close pair (or a common root) settles the two cells.
  const auto link_cells = [&](std::uint32_t b, std::uint32_t e, std::uint32_t b2, std::uint32_t e2) {
    for (std::uint32_t k = b; k < e; ++k)
      for (std::uint32_t l = b2; l < e2; ++l) {
        const std::uint32_t i = order_[k], j = order_[l];
        if (fast && find_root(parent_, i) == find_root(parent_, j)) return;
        if (!close(i, j)) continue;
        join(i, j);
        if (fast) return;
      }
  };
  for (std::int64_t c = 0; c < nx * ny; ++c) {
    const std::uint32_t b = cell_start_[static_cast<std::size_t>(c)], e = cell_start_[static_cast<std::size_t>(c) + 1];
    if (b == e) continue;
    // Within the cell.
    for (std::uint32_t k = b + 1; k < e; ++k) {
      if (fast) {
        join(order_[b], order_[k]);
        continue;
      }
      for (std::uint32_t l = b; l < k; ++l)
        if (close(order_[k], order_[l])) join(order_[k], order_[l]);
    }
    // With each later neighbouring cell: one close pair joins them.
    const std::int64_t cx = c % nx, cy = c / nx;
    for (std::int64_t yy = std::max<std::int64_t>(0, cy - reach); yy <= std::min(ny - 1, cy + reach); ++yy)
      for (std::int64_t xx = std::max<std::int64_t>(0, cx - reach); xx <= std::min(nx - 1, cx + reach); ++xx) {
        const std::int64_t d = yy * nx + xx;
        if (d <= c) continue;
        const std::uint32_t b2 = cell_start_[static_cast<std::size_t>(d)],
                            e2 = cell_start_[static_cast<std::size_t>(d) + 1];
        if (b2 == e2) continue;
        link_cells(b, e, b2, e2);
      }
  }
  // Components in order of their first point, so the output is deterministic.
  std::vector<Cluster> out;
  std::vector<std::uint32_t> slot(n, std::numeric_limits<std::uint32_t>::max());
  for (std::uint32_t i = 0; i < n; ++i) {
    const std::uint32_t r = find_root(parent_, i);
    if (slot[r] == std::numeric_limits<std::uint32_t>::max()) {
      slot[r] = static_cast<std::uint32_t>(out.size());
      out.emplace_back();
    }
    out[slot[r]].indices.push_back(i);
  }
  return out;
}

std::vector<Cluster> Clusterer::cluster_pcl(const std::vector<Point>& points) const {
  if (points.empty()) return {};
  pcl::PointCloud<pcl::PointXYZ>::Ptr cloud(new pcl::PointCloud<pcl::PointXYZ>);
  cloud->points.reserve(points.size());
  const float zw = static_cast<float>(cfg_.z_weight);
  for (const auto& q : points) cloud->points.emplace_back(q.x, q.y, zw * q.z);
  cloud->width = static_cast<std::uint32_t>(cloud->points.size());
  cloud->height = 1;
  pcl::search::KdTree<pcl::PointXYZ>::Ptr tree(new pcl::search::KdTree<pcl::PointXYZ>);
  tree->setInputCloud(cloud);
  pcl::EuclideanClusterExtraction<pcl::PointXYZ> ec;
  ec.setClusterTolerance(cfg_.tolerance);
  ec.setMinClusterSize(1);
  ec.setMaxClusterSize(std::numeric_limits<int>::max());
  ec.setSearchMethod(tree);
  ec.setInputCloud(cloud);
  std::vector<pcl::PointIndices> found;
  ec.extract(found);
  std::vector<Cluster> out;
  out.reserve(found.size());
  for (const auto& f : found) {
    Cluster c;
    c.indices.reserve(f.indices.size());
    for (int i : f.indices) c.indices.push_back(static_cast<std::uint32_t>(i));
    std::sort(c.indices.begin(), c.indices.end());
    out.push_back(std::move(c));
  }
  // Same order as the grid's: by first point.
  std::sort(out.begin(), out.end(),
            [](const Cluster& a, const Cluster& b) { return a.indices.front() < b.indices.front(); });
  return out;
}

}  // namespace fsd
