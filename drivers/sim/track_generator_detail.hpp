#pragma once
// Pieces shared by the layout generator's kinds (drivers/sim/track_generator*.cpp); not a public interface.
#include <vector>

#include "common/track.hpp"
#include "drivers/sim/track_generator.hpp"
#include "drivers/sim/world_random.hpp"

namespace fsd::sim::detail {

// A value of [lo, hi]: `edge_share` of the draws exactly at `edge` (lo or hi), the rest uniform over the range.
double sample_range(Rng& rng, double lo, double hi, double edge_share, double edge);

void add_cone(Track& track, ConeRole role, const Vec2& p);

// Positions of cones along a polyline (closed: its last point joins its first) with no gap longer than the
// spacing asked at each point (`spacing[i]` at `line[i]`, the smallest within reach is used), spread evenly
// between anchors: points (indices into `line`, ascending) that must carry a cone. An open line always has
// cones at both ends; a closed one without anchors starts at index 0.
std::vector<Vec2> place_cones(const std::vector<Vec2>& line, const std::vector<double>& spacing, bool closed,
                              std::vector<std::size_t> anchors);

// The kinds (track_generator_loop.cpp, track_generator_events.cpp). Options are valid.
Track generate_loop(const TrackGeneratorOptions& o);
Track generate_acceleration(const TrackGeneratorOptions& o);
Track generate_skidpad(const TrackGeneratorOptions& o);

}  // namespace fsd::sim::detail
