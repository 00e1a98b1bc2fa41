#pragma once
// Where the track is: its two boundaries as segment sets built from the cones, so the world can keep distractors
// off the track and lay grass at a distance from it.
//
// Each cone is put on the left or right side (by its role; orange and timing cones join the side of the nearer
// blue or yellow cone). Cones of one role and side are chained to their nearest neighbour and the nearest one on
// its far side within a gap, and chain ends are joined to the next cone of any role on their side, which follows
// the boundaries without relying on the order of the track file. A point is on the track when the nearest points
// of the two boundaries lie on opposite sides of it and not farther apart than a track is wide.
#include <optional>
#include <vector>

#include "common/track.hpp"

namespace fsd::sim {

class TrackArea {
 public:
  enum class Side : std::uint8_t { Left, Right };
  struct Segment {
    Vec2 a, b;
    Side side;
  };

  static constexpr double kMaxTrackWidth = 8.0;  // m; FS tracks are 3 m (trackdrive) to 5 m (acceleration)

  explicit TrackArea(const Track& track, double max_gap = 7.0);

  const std::vector<Segment>& segments() const { return segments_; }
  const std::vector<Vec2>& cone_positions() const { return cones_; }

  double distance_to_boundary(const Vec2& p) const;
  std::optional<Vec2> nearest_on_side(const Vec2& p, Side side) const;
  bool on_track(const Vec2& p) const;
  // Unit direction from the track towards the outside at cone i (away from the opposite boundary).
  std::optional<Vec2> outward_at_cone(std::size_t i) const;

 private:
  std::vector<Vec2> cones_;
  std::vector<Side> sides_;
  std::vector<Segment> segments_;
};

Vec2 closest_point_on_segment(const Vec2& p, const Vec2& a, const Vec2& b);

}  // namespace fsd::sim
