#include "drivers/sim/world/world_config.hpp"

namespace fsd::sim {

const ConfigSection<WorldConfig>& world_section() {
  using C = WorldConfig;
  static const auto s =
      ConfigSection<C>("sim.world")
          .number("ground_slope_x", &C::ground_slope_x, -0.15, 0.15, "m/m",
                  "Ground slope along map x: z = sx·x + sy·y.")
          .number("ground_slope_y", &C::ground_slope_y, -0.15, 0.15, "m/m", "Ground slope along map y.")
          .number("ground_reflectivity", &C::ground_reflectivity, 0.0, 255.0, "",
                  "LiDAR reflectivity of the track surface (VLP-16 scale: 0..100 diffuse, 101..255 retro-reflective).")
          .number("ground_texture", &C::ground_texture, 0.0, 50.0, "",
                  "Amplitude of the smooth reflectivity/brightness pattern on the ground.")
          .boolean("grass_edges", &C::grass_edges, "Grass beyond grass_offset from the track boundaries.")
          .number("grass_offset", &C::grass_offset, 2.5, 50.0, "m",
                  "Distance from the nearest boundary where asphalt turns to grass (more than half the track width).")
          .number("grass_reflectivity", &C::grass_reflectivity, 0.0, 255.0, "", "LiDAR reflectivity of grass.")
          .boolean("distractors", &C::distractors, "Place tyres, posts, tyre stacks and a fence outside the track.")
          .integer("tyres", &C::tyres, 0, 200, "", "Single tyres (0.6 m diameter, 0.2 m wide), lying or standing.")
          .integer("posts", &C::posts, 0, 200, "", "Posts (0.1 m diameter, 1.2 m high).")
          .integer("tyre_stacks", &C::tyre_stacks, 0, 200, "", "Stacks of 2 to 4 tyres.")
          .number("distractor_min_offset", &C::distractor_min_offset, 0.3, 20.0, "m",
                  "Least distance between a distractor's edge and the nearest track boundary.")
          .number("distractor_max_offset", &C::distractor_max_offset, 0.5, 30.0, "m",
                  "Greatest distance of a tyre, post or stack from the boundary it is placed next to.")
          .boolean("fence", &C::fence, "Fence segments along the outside of the track.")
          .integer("fence_segments", &C::fence_segments, 0, 50, "", "Number of straight fence segments.")
          .number("fence_length", &C::fence_length, 2.0, 100.0, "m",
                  "Length of a fence segment (shortened to fit bends).")
          .number("fence_height", &C::fence_height, 0.5, 3.0, "m", "Height of the fence.")
          .number("fence_offset_min", &C::fence_offset_min, 1.0, 50.0, "m",
                  "Least distance of the fence from the track.")
          .number("fence_offset_max", &C::fence_offset_max, 1.0, 50.0, "m",
                  "Greatest distance of the fence from the track.");
  return s;
}

}  // namespace fsd::sim
