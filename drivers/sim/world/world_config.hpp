#pragma once
// Configuration of the virtual world (ground, grass, distractors). Keys under "sim.world".
#include "common/config.hpp"

namespace fsd::sim {

struct WorldConfig {
  // Ground plane z = ground_slope_x·x + ground_slope_y·y (map frame).
  double ground_slope_x = 0.0;
  double ground_slope_y = 0.0;
  double ground_reflectivity = 12.0;  // asphalt, VLP-16 calibrated reflectivity
  double ground_texture = 4.0;        // amplitude of the smooth reflectivity/brightness noise on the ground
  // Grass beyond this distance from the track boundaries (the infield too).
  bool grass_edges = true;
  double grass_offset = 3.5;  // m from the nearest boundary; must exceed half the track width
  double grass_reflectivity = 45.0;
  // Objects outside the track that a LiDAR alone takes for cones, placed by the seed.
  bool distractors = true;
  int tyres = 8;
  int posts = 6;
  int tyre_stacks = 4;
  double distractor_min_offset = 1.0;  // m outside the boundary (edge of the object)
  double distractor_max_offset = 5.0;
  bool fence = true;
  int fence_segments = 3;
  double fence_length = 15.0;
  double fence_height = 1.5;
  double fence_offset_min = 5.0;
  double fence_offset_max = 8.0;
};

const ConfigSection<WorldConfig>& world_section();  // prefix "sim.world"

}  // namespace fsd::sim
