#pragma once
// The ground of the virtual world: a (possibly sloped) plane, asphalt near the track and grass beyond an
// irregular edge at a distance from the boundaries, with a smooth reflectivity texture seeded by the world seed.
#include <cstdint>
#include <vector>

#include "common/geometry.hpp"
#include "drivers/sim/world/world_config.hpp"
#include "drivers/sim/world/world_track_area.hpp"

namespace fsd::sim {

enum class Surface : std::uint8_t { None, Ground, Grass, ConeBody, ConeStripe, Tyre, Post, Fence };

class Ground {
 public:
  Ground(const WorldConfig& cfg, const TrackArea& area, std::uint64_t seed);

  double slope_x() const { return sx_; }
  double slope_y() const { return sy_; }
  double height(double x, double y) const { return sx_ * x + sy_ * y; }
  Vec3 normal() const { return normal_; }
  Surface surface(double x, double y) const;  // Ground (asphalt) or Grass
  double reflectivity(double x, double y) const { return reflectivity(x, y, surface(x, y)); }
  double reflectivity(double x, double y, Surface surface_there) const;

 private:
  double sx_, sy_;
  Vec3 normal_;
  double asphalt_reflectivity_, grass_reflectivity_, texture_;
  std::uint64_t seed_;
  bool grass_;
  // Raster of "asphalt" flags over the track's surroundings; outside it everything is grass.
  double x0_ = 0, y0_ = 0, cell_ = 0.2;
  int nx_ = 0, ny_ = 0;
  std::vector<std::uint8_t> asphalt_;
};

}  // namespace fsd::sim
