#pragma once
// Laps from crossings of the timing line: the segment between the big orange cones at the start/finish, or,
// on a layout without timing cones, a line across the track through the start pose. A crossing counts in the
// direction of travel only, with hysteresis (the car must get well away from the line before the next one
// counts, and a lap has a minimum time). Lap times run line crossing to line crossing.
#include <optional>
#include <vector>

#include "common/track.hpp"
#include "common/types.hpp"

namespace fsd {

struct TimingLine {
  Vec2 a = Vec2::Zero(), b = Vec2::Zero();  // ends across the track
  Vec2 forward = Vec2::UnitX();             // unit direction of travel across the line
  Vec2 mid() const { return 0.5 * (a + b); }
  // Signed distance of p past the line along `forward` (negative before it).
  double past(const Vec2& p) const { return (p - mid()).dot(forward); }
};

// The timing line nearest ahead of (or just behind) `start` from the timing-coloured cones, pairing the cones
// left and right of the start heading. `index` picks the 0th, 1st, ... group along the heading (an
// acceleration track has a start and a finish line). With timing cones on one side only, the line runs across the
// start heading from them one nominal track width (3.5 m) towards the other side; nullopt without any.
// `both_sides`: nullopt unless the group has timing cones on both sides (one misnamed cone is no line).
std::optional<TimingLine> timing_line_from_cones(const std::vector<Cone>& cones, const Pose2& start,
                                                 const ColourConvention& convention, int index = 0,
                                                 double search_behind = 10.0, double search_ahead = 40.0,
                                                 bool both_sides = false);
// A line across the heading through `pose`, `half_width` to each side.
TimingLine line_across(const Pose2& pose, double half_width = 5.0);

struct LapCounterConfig {
  // m driven since the previous crossing (or the start at the line), clear of the line, before the next one counts:
  // a line crossed to and fro by the pose's jitter counts once, and a lap of any length above this counts (a lap
  // round one 9 m turn is 19 m, and never more than 6 m from its line).
  double hysteresis = 10.0;
  double min_lap_time = 2.0;  // s: crossings closer in time than this are ignored
  double line_margin = 1.5;   // m: the line's ends are extended by this (cones are on the boundary)
};

struct LapEvent {
  int lap = 0;        // number of the lap just completed (1 = first)
  Stamp t = 0;        // time of the crossing (interpolated)
  double time_s = 0;  // lap time, crossing to crossing (or from the start when it began past the line)
};

class LapCounter {
 public:
  LapCounter(TimingLine line, LapCounterConfig config = {});

  // Feeds one rear-axle position; returns the completed lap when this step crossed the line.
  std::optional<LapEvent> update(Stamp t, const Vec2& position);

  // The car started past the line but close to it (a layout whose start pose is after the line): the first
  // lap is timed from `t` and ends at the first crossing.
  void start_timing_at(Stamp t);

  bool timing() const { return lap_start_.has_value(); }  // a lap is being timed
  int laps_completed() const { return static_cast<int>(lap_times_.size()); }
  const std::vector<double>& lap_times() const { return lap_times_; }
  std::optional<Stamp> last_crossing() const { return last_crossing_; }
  const TimingLine& line() const { return line_; }

 private:
  TimingLine line_;
  LapCounterConfig config_;
  std::optional<Vec2> prev_;
  Stamp prev_t_ = 0;
  bool armed_ = true;
  double since_crossing_ = 0;  // m driven since the car was last at the line
  std::optional<Stamp> lap_start_, last_crossing_;
  std::vector<double> lap_times_;
};

}  // namespace fsd
