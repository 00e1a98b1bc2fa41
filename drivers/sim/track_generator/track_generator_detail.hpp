#pragma once
// Pieces shared by the layout generator's kinds (drivers/sim/track_generator*.cpp); not a public interface.
#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include "common/track.hpp"
#include "drivers/sim/track_generator/centre_line_builder.hpp"
#include "drivers/sim/track_generator/track_generator.hpp"
#include "drivers/sim/world/world_random.hpp"

namespace fsd::sim::detail {

inline constexpr double kLaneMin = 3.0;             // m: the rules' minimum track width
inline constexpr double kHairpinOuterMin = 4.5;     // m: the rules' 9 m outside diameter
inline constexpr double kStartLine = 6.0;           // m from car_start to the start line (the shared EPFL files)
inline constexpr double kTimingHalfGap = 0.6;       // m either side of a timing line to its big orange cones
inline constexpr double kStraightCurvature = 0.02;  // 1/m: straighter than half the widest turn counts as straight

// A value of [lo, hi]: `edge_share` of the draws exactly at `edge` (lo or hi), the rest uniform over the range.
double sample_range(Rng& rng, double lo, double hi, double edge_share, double edge);

void add_cone(Track& track, ConeRole role, const Vec2& p);

// Positions of cones along a polyline (closed: its last point joins its first) with no gap longer than the
// spacing asked at each point (`spacing[i]` at `line[i]`, the smallest within reach is used), spread evenly
// between anchors: points (indices into `line`, ascending) that must carry a cone. An open line always has
// cones at both ends; a closed one without anchors starts at index 0.
std::vector<Vec2> place_cones(const std::vector<Vec2>& line, const std::vector<double>& spacing, bool closed,
                              std::vector<std::size_t> anchors);

// A cone of place_cones_along: where it stands and the segment of the line it stands on (line[index] to the
// next point; an open line's last cone has the last index).
struct PlacedCone {
  Vec2 p = Vec2::Zero();
  std::size_t index = 0;
};

// place_cones, with each cone's segment, and uneven gaps when `spacing_jitter` S > 0: each cone between anchors
// moves along the line by up to S/2 of the even gap (draws from `rng`), so neighbouring gaps differ by up to S
// of it either way. Pass the spacing divided by (1 + S) to keep every gap within what was meant.
std::vector<PlacedCone> place_cones_along(const std::vector<Vec2>& line, const std::vector<double>& spacing,
                                          bool closed, std::vector<std::size_t> anchors, double spacing_jitter = 0.0,
                                          Rng* rng = nullptr);

// Hand placement: an offset drawn uniformly in a disc of radius `jitter`, as (along the boundary, outward from
// the lane). Where the lane may give up only `inward_room` m, an offset further inward is mirrored outward.
Vec2 hand_offset(Rng& rng, double jitter, double inward_room);

// A trackdrive/autocross centre line as drawn (track_generator_loop.cpp) and the values fixed per layout.
struct LoopLayout {
  double width = 3, spacing = 5, yaw0 = 0;
  double rc_min = 3;  // m: the tightest centre-line radius (9 m outside, and the island inside a hairpin)
};

struct LoopCandidate {
  std::vector<CentreSample> line;
  std::vector<std::pair<std::size_t, int>> anchors;  // slalom cones: sample index, side (+1 left, -1 right)
  double start_s = 0;                                // car_start's arc length
  double end_s = 0;                                  // open: the finish line's arc length
  int chains = 0;                                    // hairpin chains drawn
};

// The cones of an accepted loop, with the hand-placement options (track_generator_cones.cpp); `hand` draws
// what they need. Nothing when the options ask for a feature the line has no place for (a narrowing without a
// straight, an outlier without a tight turn): the caller draws the next candidate.
std::optional<Track> loop_cones(const LoopCandidate& c, const TrackGeneratorOptions& o, const LoopLayout& lay,
                                Rng& hand);

// The kinds (track_generator_loop.cpp, track_generator_events.cpp, track_generator_circle.cpp). Options are valid.
Track generate_loop(const TrackGeneratorOptions& o);
Track generate_circle(const TrackGeneratorOptions& o);
Track generate_acceleration(const TrackGeneratorOptions& o);
Track generate_skidpad(const TrackGeneratorOptions& o);

}  // namespace fsd::sim::detail
