#pragma once
// Objects outside the track that a LiDAR alone takes for cones: single tyres, posts, tyre stacks, and fence
// segments. Placed by seed next to the boundaries (the infield too), never on the track, never nearer to a
// boundary than the configured offset, never overlapping each other.
#include <cstdint>
#include <vector>

#include "common/geometry.hpp"
#include "drivers/sim/world/world_config.hpp"
#include "drivers/sim/world/world_track_area.hpp"

namespace fsd::sim {

enum class DistractorType : std::uint8_t { Tyre, TyreStack, Post, Fence };
const char* to_string(DistractorType t);

struct Distractor {
  DistractorType type = DistractorType::Tyre;
  Vec2 position = Vec2::Zero();  // centre of the footprint; fence: start of the segment
  double yaw = 0.0;              // fence: direction of the segment; standing tyre: direction of its axle
  double radius = 0.0;           // tyre, stack, post
  double width = 0.0;            // tyre width (one tyre of a stack)
  double length = 0.0;           // fence segment length
  double height = 0.0;           // top above the ground
  bool standing = false;         // a single tyre on its tread, axle horizontal (else lying flat)
  int tyre_count = 1;            // tyres in a stack

  // Radius of the circle around `position` that holds the footprint (not for fences).
  double footprint_radius() const;
  Vec2 fence_end() const;  // other end of a fence segment
};

std::vector<Distractor> place_distractors(const TrackArea& area, const WorldConfig& cfg, std::uint64_t seed);

}  // namespace fsd::sim
