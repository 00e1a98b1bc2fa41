#include "localization/lidar_odometry/features.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace fsd::lidar_odometry {

namespace {
Vec3 xyz(const Point& p) { return {p.x, p.y, p.z}; }
}  // namespace

Features FeatureExtractor::extract(const Scan& scan) const {
  int rings = 0;
  for (const auto& p : scan.points) rings = std::max(rings, int(p.ring) + 1);
  std::vector<std::vector<const Point*>> by_ring(static_cast<std::size_t>(rings));
  for (const auto& p : scan.points) {
    const double r = xyz(p).norm();
    if (r < cfg_.min_range || r > cfg_.max_range || !std::isfinite(r)) continue;
    by_ring[p.ring].push_back(&p);
  }
  Features out;
  for (auto& ring : by_ring) {
    // Neighbours in eq. 5 are neighbours in azimuth; firing order is azimuth order within a revolution, the sort
    // only guards against a cut that starts mid-revolution.
    std::stable_sort(ring.begin(), ring.end(), [](const Point* a, const Point* b) { return a->t < b->t; });
    extract_ring(ring, out);
  }
  return out;
}

void FeatureExtractor::extract_ring(const std::vector<const Point*>& ring, Features& out) const {
  const int n = int(ring.size()), k = cfg_.neighbours;
  if (n < 2 * k + 1) return;
  std::vector<Vec3> x(static_cast<std::size_t>(n));
  std::vector<double> r(static_cast<std::size_t>(n)), c(static_cast<std::size_t>(n), 0.0);
  for (int i = 0; i < n; ++i) x[i] = xyz(*ring[i]), r[i] = x[i].norm();
  // picked: excluded from selection (unreliable, or next to a point already chosen).
  std::vector<char> picked(static_cast<std::size_t>(n), 0);
  for (int i = 0; i < k; ++i) picked[i] = picked[n - 1 - i] = 1;
  for (int i = k; i < n - k; ++i) {
    Vec3 s = Vec3::Zero();
    for (int j = i - k; j <= i + k; ++j) s += x[j] - x[i];
    c[i] = s.norm() / (2.0 * k * r[i]);
  }
  for (int i = k; i < n - k - 1; ++i) {
    // Occlusion: a range jump between neighbours that is not just a surface seen obliquely. The far side's points
    // lie next to a shadow that moves with the sensor: reject them.
    const double gap = (x[i + 1] - x[i]).norm();
    if (gap > cfg_.occlusion_gap * std::min(r[i], r[i + 1])) {
      if (r[i] > r[i + 1]) {
        if ((x[i + 1] - x[i] * (r[i + 1] / r[i])).norm() < cfg_.occlusion_gap * r[i + 1])
          for (int j = std::max(0, i - k); j <= i; ++j) picked[j] = 1;
      } else if ((x[i + 1] * (r[i] / r[i + 1]) - x[i]).norm() < cfg_.occlusion_gap * r[i]) {
        for (int j = i + 1; j <= std::min(n - 1, i + 1 + k); ++j) picked[j] = 1;
      }
    }
  }
  for (int i = k; i < n - k; ++i) {
    // Parallel beam: both neighbours far compared with the range, the surface grazes the beam.
    const double lim = cfg_.parallel_beam_ratio * r[i];
    if ((x[i] - x[i - 1]).norm() > lim && (x[i + 1] - x[i]).norm() > lim) picked[i] = 1;
  }
  const int sectors = std::max(1, cfg_.sectors);
  std::vector<int> idx;
  for (int s = 0; s < sectors; ++s) {
    const int a = k + (n - 2 * k) * s / sectors, b = k + (n - 2 * k) * (s + 1) / sectors;
    if (b <= a) continue;
    idx.resize(std::size_t(b - a));
    std::iota(idx.begin(), idx.end(), a);
    std::sort(idx.begin(), idx.end(), [&](int u, int v) { return c[u] > c[v]; });
    std::vector<char> taken(picked.begin(), picked.end());
    auto suppress = [&](int i) {
      // Keep features apart: the ring neighbours of a chosen point are not chosen too (LOAM's rule).
      for (int j = std::max(0, i - k); j <= std::min(n - 1, i + k); ++j) taken[j] = 1;
    };
    int edges = 0;
    for (int i : idx) {
      if (edges >= cfg_.edges_per_sector || c[i] <= cfg_.edge_threshold) break;
      if (taken[i]) continue;
      out.edges.push_back({x[i], ring[i]->t, c[i]});
      ++edges;
      suppress(i);
    }
    int planes = 0;
    for (auto it = idx.rbegin(); it != idx.rend(); ++it) {
      const int i = *it;
      if (planes >= cfg_.planes_per_sector || c[i] >= cfg_.plane_threshold) break;
      if (taken[i]) continue;
      out.planes.push_back({x[i], ring[i]->t, c[i]});
      ++planes;
      // Planes are suppressed less: the ground is one plane and wants many points; one neighbour either side.
      taken[i] = 1;
      if (i > 0) taken[i - 1] = 1;
      if (i + 1 < n) taken[i + 1] = 1;
    }
  }
}

}  // namespace fsd::lidar_odometry
