#include "perception/ground_surface.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace fsd {

void GroundSurface::fit_local(const std::vector<Point>& points, const LocalGroundConfig& cfg) {
  offset_.clear();
  corrected_ = 0;
  nx_ = ny_ = 0;
  if (cfg.cell <= 0 || points.empty()) return;
  float xa = std::numeric_limits<float>::max(), ya = xa, xb = -xa, yb = -xa;
  for (const auto& q : points)
    xa = std::min(xa, q.x), xb = std::max(xb, q.x), ya = std::min(ya, q.y), yb = std::max(yb, q.y);
  cell_ = cfg.cell;
  while ((xb - xa) / cell_ * (yb - ya) / cell_ > 65536.0) cell_ *= 2;
  x0_ = xa, y0_ = ya;
  nx_ = static_cast<int>((xb - xa) / cell_) + 1, ny_ = static_cast<int>((yb - ya) / cell_) + 1;
  const auto cells = static_cast<std::size_t>(nx_) * static_cast<std::size_t>(ny_);
  // Residuals from the plane of the points within the band, by cell (counting sort).
  struct Sample {
    float r, x, y;
  };
  std::vector<std::uint32_t>& start = start_;
  std::vector<std::uint32_t>& cell_of = cell_of_;
  start.assign(cells + 1, 0);
  cell_of.assign(points.size(), std::numeric_limits<std::uint32_t>::max());
  residual_.resize(points.size());
  const auto index = [&](float x, float y) {
    const int cx = std::clamp(static_cast<int>((x - x0_) / cell_), 0, nx_ - 1);
    const int cy = std::clamp(static_cast<int>((y - y0_) / cell_), 0, ny_ - 1);
    return static_cast<std::uint32_t>(cy * nx_ + cx);
  };
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto& q = points[i];
    residual_[i] = static_cast<float>((q.z - plane_.z_at(q.x, q.y)) * k_);
    if (std::abs(residual_[i]) >= cfg.band) continue;
    cell_of[i] = index(q.x, q.y);
    ++start[cell_of[i] + 1];
  }
  for (std::size_t c = 0; c < cells; ++c) start[c + 1] += start[c];
  std::vector<Sample> samples(start.back());
  {
    std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
    for (std::size_t i = 0; i < points.size(); ++i)
      if (cell_of[i] != std::numeric_limits<std::uint32_t>::max()) {
        const auto& q = points[i];  // NOLINT
        samples[fill[cell_of[i]]++] = {residual_[i], q.x, q.y};
      }
  }
  // Per cell: the layer at the median of the residuals (ground returns outnumber what stands on it) and the
  // points within `flat` of it.
  offset_.assign(cells, 0.0f);
  std::vector<char> known(cells, 0);
  std::vector<float> r;
  for (std::size_t c = 0; c < cells; ++c) {
    const auto b = start[c], e = start[c + 1];
    if (e - b < static_cast<std::uint32_t>(cfg.min_points)) continue;
    r.clear();
    for (auto k = b; k < e; ++k) r.push_back(samples[k].r);
    const auto q = r.begin() + static_cast<std::ptrdiff_t>(r.size() / 2);
    std::nth_element(r.begin(), q, r.end());
    const float level = *q;
    float xa2 = std::numeric_limits<float>::max(), ya2 = xa2, xb2 = -xa2, yb2 = -xa2;
    double sum = 0, cx = 0, cy = 0;
    int n = 0;
    for (auto k = b; k < e; ++k) {
      const Sample& s = samples[k];
      if (std::abs(s.r - level) > cfg.flat) continue;
      xa2 = std::min(xa2, s.x), xb2 = std::max(xb2, s.x), ya2 = std::min(ya2, s.y), yb2 = std::max(yb2, s.y);
      sum += s.r;
      cx += s.x, cy += s.y;
      ++n;
    }
    const double extent = std::hypot(xb2 - xa2, yb2 - ya2);
    if (n < cfg.min_points || extent < cfg.min_extent) continue;
    // The returns one ring of ground gives over that spread at the layer's range (its centroid's: one root a cell).
    const double range = std::hypot(cx / n - cfg.sensor.x(), cy / n - cfg.sensor.y());
    if (cfg.azimuth_step > 0 && n < cfg.min_fill * extent / std::max(1e-3, range * cfg.azimuth_step)) continue;
    offset_[c] = static_cast<float>(sum / n);
    known[c] = 1;
    ++corrected_;
  }
  // Cells without a layer: the mean of their known neighbours, else the plane.
  std::vector<float> filled = offset_;
  for (int cy = 0; cy < ny_; ++cy)
    for (int cx = 0; cx < nx_; ++cx) {
      const auto c = static_cast<std::size_t>(cy * nx_ + cx);
      if (known[c]) continue;
      double sum = 0;
      int n = 0;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int x = cx + dx, y = cy + dy;
          if (x < 0 || y < 0 || x >= nx_ || y >= ny_) continue;
          const auto k = static_cast<std::size_t>(y * nx_ + x);
          if (known[k]) sum += offset_[k], ++n;
        }
      filled[c] = n > 0 ? static_cast<float>(sum / n) : 0.0f;
    }
  offset_ = std::move(filled);
}

double GroundSurface::offset_at(double x, double y) const {
  if (offset_.empty()) return 0.0;
  // Bilinear between cell centres, held at the outer centres.
  const double fx = std::clamp((x - x0_) / cell_ - 0.5, 0.0, static_cast<double>(nx_ - 1));
  const double fy = std::clamp((y - y0_) / cell_ - 0.5, 0.0, static_cast<double>(ny_ - 1));
  const int ix = std::min(static_cast<int>(fx), nx_ - 1), iy = std::min(static_cast<int>(fy), ny_ - 1);
  const int jx = std::min(ix + 1, nx_ - 1), jy = std::min(iy + 1, ny_ - 1);
  const double ux = fx - ix, uy = fy - iy;
  const auto at = [&](int cx, int cy) { return static_cast<double>(offset_[static_cast<std::size_t>(cy * nx_ + cx)]); };
  return (1 - uy) * ((1 - ux) * at(ix, iy) + ux * at(jx, iy)) + uy * ((1 - ux) * at(ix, jy) + ux * at(jx, jy));
}

}  // namespace fsd
