#pragma once
// The timing lines of a track as a timekeeper sees them: each group of big orange cones forms a gate, a line
// across the track perpendicular to the start heading. A track without timing cones gets one gate at the start.
// Only crossings in the driving direction count. Used by the scorecard, independently of the stack's lap counter.
#include <optional>
#include <vector>

#include "common/geometry.hpp"
#include "common/track.hpp"

namespace fsd::sim {

struct Gate {
  Vec2 centre = Vec2::Zero();
  Vec2 forward = Vec2::UnitX();  // driving direction through the gate
  double half_width = 3.0;       // lateral extent of the line, m
};

class TimingGates {
 public:
  explicit TimingGates(const Track& track);
  const std::vector<Gate>& gates() const { return gates_; }
  // Index of the gate crossed forwards by the move from a to b, if any.
  std::optional<std::size_t> crossed(const Vec2& a, const Vec2& b) const;
  // Signed distance of p past gate i along its forward direction.
  double past(std::size_t i, const Vec2& p) const;

 private:
  std::vector<Gate> gates_;
};

}  // namespace fsd::sim
