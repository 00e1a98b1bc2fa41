#include "drivers/sim/world/world_grid.hpp"

namespace fsd::sim {

void UniformGrid::build(const std::vector<Eigen::AlignedBox2d>& boxes, const std::vector<std::uint32_t>& ids,
                        double cell) {
  cell_ = cell;
  nx_ = ny_ = 0;
  start_.assign(1, 0);
  items_.clear();
  if (boxes.empty()) return;
  Eigen::AlignedBox2d all;
  for (const auto& b : boxes) all.extend(b);
  x0_ = std::floor(all.min().x() / cell) * cell - cell;
  y0_ = std::floor(all.min().y() / cell) * cell - cell;
  nx_ = static_cast<int>(std::ceil((all.max().x() - x0_) / cell)) + 1;
  ny_ = static_cast<int>(std::ceil((all.max().y() - y0_) / cell)) + 1;
  const auto cells = static_cast<std::size_t>(nx_) * static_cast<std::size_t>(ny_);

  auto for_cells = [&](const Eigen::AlignedBox2d& b, auto&& f) {
    const int ix0 = std::clamp(static_cast<int>(std::floor((b.min().x() - x0_) / cell_)), 0, nx_ - 1);
    const int ix1 = std::clamp(static_cast<int>(std::floor((b.max().x() - x0_) / cell_)), 0, nx_ - 1);
    const int iy0 = std::clamp(static_cast<int>(std::floor((b.min().y() - y0_) / cell_)), 0, ny_ - 1);
    const int iy1 = std::clamp(static_cast<int>(std::floor((b.max().y() - y0_) / cell_)), 0, ny_ - 1);
    for (int iy = iy0; iy <= iy1; ++iy)
      for (int ix = ix0; ix <= ix1; ++ix)
        f(static_cast<std::size_t>(iy) * static_cast<std::size_t>(nx_) + static_cast<std::size_t>(ix));
  };
  // Two passes: count per cell, then fill (compressed rows).
  std::vector<std::uint32_t> count(cells + 1, 0);
  for (const auto& b : boxes) for_cells(b, [&](std::size_t c) { ++count[c + 1]; });
  for (std::size_t c = 0; c < cells; ++c) count[c + 1] += count[c];
  start_ = count;
  items_.assign(start_.back(), 0);
  std::vector<std::uint32_t> fill(start_.begin(), start_.end() - 1);
  for (std::size_t i = 0; i < boxes.size(); ++i)
    for_cells(boxes[i], [&](std::size_t c) { items_[fill[c]++] = ids[i]; });
}

}  // namespace fsd::sim
