#pragma once
// A track's centre line built piece by piece from its end pose, as dense samples (every `ds` metres) that carry
// their heading and curvature: straights, arcs, clothoids (curvature linear in arc length), a slalom wave and
// the shortest Dubins connection to a pose. Used by the layout generator (drivers/sim/track_generator).
#include <optional>
#include <vector>

#include "common/geometry.hpp"

namespace fsd::sim {

struct CentreSample {
  Vec2 p = Vec2::Zero();
  double heading = 0;  // rad
  double kappa = 0;    // 1/m, left positive
  double s = 0;        // m from the first sample
};

class CentreLineBuilder {
 public:
  explicit CentreLineBuilder(const Pose2& start, double ds = 0.1);

  void straight(double length);
  // Signed angle: positive turns left.
  void arc(double radius, double angle);
  void clothoid(double kappa0, double kappa1, double length);
  // A wave of `half_periods` bends whose extremes, `half_period` m apart along the current heading, alternate
  // between the start's lateral position and 2·amplitude to the side `side` (+1 left, -1 right). The wave
  // starts and ends on the heading it started with. Returns the sample index of each extreme (half_periods + 1,
  // the first being the current end).
  std::vector<std::size_t> slalom(double half_period, int half_periods, double amplitude, int side);
  // The shortest path of arcs of `radius` and a straight (or three arcs) to `goal`; false when there is none.
  bool dubins_to(const Pose2& goal, double radius);

  Pose2 end() const;
  double length() const { return samples_.back().s; }
  const std::vector<CentreSample>& samples() const { return samples_; }

 private:
  void push(const Vec2& p, double heading, double kappa, double ds);
  std::vector<CentreSample> samples_;
  double ds_;
};

}  // namespace fsd::sim
