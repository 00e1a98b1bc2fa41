#include "drivers/sim/world/world_ground.hpp"

#include <algorithm>
#include <cmath>

#include "drivers/sim/world/world_random.hpp"

namespace fsd::sim {

namespace {
constexpr double kGrassEdgeJitter = 0.8;  // m: the grass edge wanders this much around grass_offset
constexpr double kGrassEdgeWavelength = 4.0;
constexpr std::uint64_t kTextureStream = 0x7E27u;
constexpr std::uint64_t kGrassStream = 0x62A55u;
}  // namespace

Ground::Ground(const WorldConfig& cfg, const TrackArea& area, std::uint64_t seed)
    : sx_(cfg.ground_slope_x),
      sy_(cfg.ground_slope_y),
      normal_(Vec3(-cfg.ground_slope_x, -cfg.ground_slope_y, 1.0).normalized()),
      asphalt_reflectivity_(cfg.ground_reflectivity),
      grass_reflectivity_(cfg.grass_reflectivity),
      texture_(cfg.ground_texture),
      seed_(seed),
      grass_(cfg.grass_edges) {
  if (!grass_ || area.segments().empty()) return;
  const double reach = cfg.grass_offset + kGrassEdgeJitter;
  Eigen::AlignedBox2d box;
  for (const auto& p : area.cone_positions()) box.extend(p);
  box.min() -= Vec2::Constant(reach + 1.0);
  box.max() += Vec2::Constant(reach + 1.0);
  x0_ = box.min().x();
  y0_ = box.min().y();
  nx_ = static_cast<int>(std::ceil(box.sizes().x() / cell_));
  ny_ = static_cast<int>(std::ceil(box.sizes().y() / cell_));
  asphalt_.assign(static_cast<std::size_t>(nx_) * static_cast<std::size_t>(ny_), 0);
  // Rasterise each boundary segment's neighbourhood: asphalt where the cell is nearer than the wandering edge.
  const std::uint64_t edge_seed = hash64(seed, kGrassStream);
  for (const auto& s : area.segments()) {
    const int ix0 = std::max(0, static_cast<int>((std::min(s.a.x(), s.b.x()) - reach - x0_) / cell_));
    const int ix1 = std::min(nx_ - 1, static_cast<int>((std::max(s.a.x(), s.b.x()) + reach - x0_) / cell_));
    const int iy0 = std::max(0, static_cast<int>((std::min(s.a.y(), s.b.y()) - reach - y0_) / cell_));
    const int iy1 = std::min(ny_ - 1, static_cast<int>((std::max(s.a.y(), s.b.y()) + reach - y0_) / cell_));
    for (int iy = iy0; iy <= iy1; ++iy) {
      for (int ix = ix0; ix <= ix1; ++ix) {
        auto& flag =
            asphalt_[static_cast<std::size_t>(iy) * static_cast<std::size_t>(nx_) + static_cast<std::size_t>(ix)];
        if (flag) continue;
        const Vec2 c(x0_ + (ix + 0.5) * cell_, y0_ + (iy + 0.5) * cell_);
        const double d = (closest_point_on_segment(c, s.a, s.b) - c).norm();
        if (d > reach) continue;
        const double edge =
            cfg.grass_offset + kGrassEdgeJitter * value_noise(edge_seed, c.x(), c.y(), kGrassEdgeWavelength);
        if (d < edge) flag = 1;
      }
    }
  }
}

Surface Ground::surface(double x, double y) const {
  if (!grass_) return Surface::Ground;
  const int ix = static_cast<int>(std::floor((x - x0_) / cell_));
  const int iy = static_cast<int>(std::floor((y - y0_) / cell_));
  if (ix < 0 || iy < 0 || ix >= nx_ || iy >= ny_) return Surface::Grass;
  return asphalt_[static_cast<std::size_t>(iy) * static_cast<std::size_t>(nx_) + static_cast<std::size_t>(ix)]
             ? Surface::Ground
             : Surface::Grass;
}

double Ground::reflectivity(double x, double y, Surface surface_there) const {
  const double base = surface_there == Surface::Grass ? grass_reflectivity_ : asphalt_reflectivity_;
  if (texture_ <= 0.0) return base;
  const std::uint64_t s = hash64(seed_, kTextureStream);
  // Smooth patches of a couple of metres with a 10 cm grain on top.
  const double grain = 2.0 * unit_double(lattice_hash(s, static_cast<std::int64_t>(std::floor(x * 10.0)),
                                                      static_cast<std::int64_t>(std::floor(y * 10.0)))) -
                       1.0;
  const double n = 0.6 * value_noise(s, x, y, 2.0) + 0.4 * grain;
  return std::clamp(base + texture_ * n, 0.0, 255.0);
}

}  // namespace fsd::sim
