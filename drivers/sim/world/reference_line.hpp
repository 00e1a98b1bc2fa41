#pragma once
// The track's true centre line, computed from the true cones alone. It is the yardstick of the scorecard's
// cross-track error (DESIGN.md §8), so it shares no code with the planner it measures.
#include <optional>
#include <vector>

#include "common/geometry.hpp"
#include "common/track.hpp"

namespace fsd::sim {

class ReferenceLine {
 public:
  // Each boundary is its cones as the file lists them when that is a line (an open course, which may begin behind
  // the start pose), else a nearest-neighbour chain from the cones nearest the start, untangled into a loop when it
  // closes; in the start heading's direction. The centre line is the midpoint of each left-boundary sample and its
  // closest right-boundary point.
  explicit ReferenceLine(const Track& track, double spacing = 0.25);

  const std::vector<Vec2>& points() const { return centre_; }
  bool closed() const { return closed_; }
  double length() const { return length_; }
  // Unsigned distance from p to the centre line polyline.
  double distance(const Vec2& p) const;
  const std::vector<Vec2>& left() const { return left_; }
  const std::vector<Vec2>& right() const { return right_; }

 private:
  std::vector<Vec2> left_, right_, centre_;
  bool closed_ = false;
  double length_ = 0;
};

}  // namespace fsd::sim
