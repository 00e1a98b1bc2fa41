#pragma once
// Small helpers shared by the world and LiDAR tests: hand-built tracks and configurations.
#include <vector>

#include "common/track.hpp"
#include "drivers/sim/world/world.hpp"

namespace fsd::sim::test {

inline TrackCone make_cone(double x, double y, ConeRole role = ConeRole::Left) {
  TrackCone c;
  c.position = Vec2(x, y);
  c.role = role;
  c.colour = ColourConvention{}.colour_of(role);
  return c;
}

inline Track make_track(std::vector<TrackCone> cones) {
  Track t;
  t.name = "hand_made";
  t.cones = std::move(cones);
  return t;
}

// Only the cones: no distractors, no grass, no texture, flat.
inline WorldConfig bare_config() {
  WorldConfig c;
  c.distractors = false;
  c.grass_edges = false;
  c.ground_texture = 0.0;
  return c;
}

}  // namespace fsd::sim::test
