#include "control/missions/lap_counter.hpp"

#include <algorithm>
#include <cmath>

namespace fsd {

TimingLine line_across(const Pose2& pose, double half_width) {
  TimingLine l;
  l.forward = Vec2(std::cos(pose.yaw), std::sin(pose.yaw));
  const Vec2 left(-l.forward.y(), l.forward.x());
  l.a = pose.position() + half_width * left;
  l.b = pose.position() - half_width * left;
  return l;
}

std::optional<TimingLine> timing_line_from_cones(const std::vector<Cone>& cones, const Pose2& start,
                                                 const ColourConvention& convention, int index, double search_behind,
                                                 double search_ahead, bool both_sides) {
  struct Local {
    Vec2 map, local;
  };
  std::vector<Local> timing;
  for (const auto& c : cones) {
    if (!c.position.allFinite() || convention.role_of(c.colour) != ConeRole::Timing) continue;
    const Vec2 m = c.position.head<2>();
    const Vec2 l = start.inverse_transform(m);
    if (l.x() < -search_behind || std::abs(l.y()) > 6.0) continue;
    timing.push_back({m, l});
  }
  std::sort(timing.begin(), timing.end(), [](const Local& a, const Local& b) { return a.local.x() < b.local.x(); });
  // Groups along the heading: a gap of more than 5 m starts the next line.
  int group = 0;
  std::vector<Local> chosen;
  for (std::size_t i = 0; i < timing.size(); ++i) {
    if (i > 0 && timing[i].local.x() - timing[i - 1].local.x() > 5.0) ++group;
    if (group == index) chosen.push_back(timing[i]);
  }
  Vec2 left_sum = Vec2::Zero(), right_sum = Vec2::Zero();
  int nl = 0, nr = 0;
  for (const auto& t : chosen) {
    if (t.local.x() > search_ahead) continue;
    if (t.local.y() > 0) {
      left_sum += t.map;
      ++nl;
    } else {
      right_sum += t.map;
      ++nr;
    }
  }
  if ((nl == 0 && nr == 0) || (both_sides && (nl == 0 || nr == 0))) return std::nullopt;
  const Vec2 heading(std::cos(start.yaw), std::sin(start.yaw));
  if (nl == 0 || nr == 0) {
    // Timing cones on one side only: a cone map merges a start line's doubled cones with the boundary cone
    // beside them and may vote that one the boundary's colour. The line then runs across the start heading from
    // the side that is seen, one nominal track width over to the other.
    constexpr double kNominalWidth = 3.5;
    const Vec2 left(-heading.y(), heading.x());
    TimingLine line;
    line.forward = heading;
    if (nl > 0) {
      line.a = left_sum / nl;
      line.b = line.a - kNominalWidth * left;
    } else {
      line.b = right_sum / nr;
      line.a = line.b + kNominalWidth * left;
    }
    return line;
  }
  TimingLine line;
  line.a = left_sum / nl;
  line.b = right_sum / nr;
  const Vec2 across = line.a - line.b;  // right → left
  if (across.norm() < 1.0) return std::nullopt;
  line.forward = Vec2(across.y(), -across.x()).normalized();
  if (line.forward.dot(heading) < 0) line.forward = -line.forward;
  return line;
}

LapCounter::LapCounter(TimingLine line, LapCounterConfig config) : line_(line), config_(config) {}

void LapCounter::start_timing_at(Stamp t) {
  if (!lap_start_) lap_start_ = t;
  armed_ = false;  // the car is at the line already; it must drive away before a crossing counts
  since_crossing_ = 0;
}

std::optional<LapEvent> LapCounter::update(Stamp t, const Vec2& position) {
  if (!position.allFinite() || !std::isfinite(t)) return std::nullopt;
  std::optional<LapEvent> event;
  // Armed again once the car has driven `hysteresis` and stands clear of the line: a pose jittering across the line
  // drives metres without leaving it, and a lap round one 9 m turn never goes farther than 6 m from its line.
  constexpr double kClearOfLine = 2.0;  // m
  if (prev_) since_crossing_ += (position - *prev_).norm();
  if (!armed_ && since_crossing_ > config_.hysteresis && (position - line_.mid()).norm() > kClearOfLine) armed_ = true;
  if (prev_ && armed_) {
    const double p0 = line_.past(*prev_), p1 = line_.past(position);
    if (p0 <= 0 && p1 > 0) {
      // Where the step crosses the line, and whether that is between the (extended) ends.
      const double f = p0 == p1 ? 0.0 : -p0 / (p1 - p0);
      const Vec2 x = *prev_ + f * (position - *prev_);
      const Vec2 along = (line_.b - line_.a);
      const double half = 0.5 * along.norm() + config_.line_margin;
      const bool within = std::abs((x - line_.mid()).dot(along.normalized())) <= half;
      const Stamp tc = prev_t_ + f * (t - prev_t_);
      const bool too_soon = last_crossing_ && tc - *last_crossing_ < config_.min_lap_time;
      if (within && !too_soon) {
        if (lap_start_) {
          lap_times_.push_back(tc - *lap_start_);
          event = LapEvent{static_cast<int>(lap_times_.size()), tc, lap_times_.back()};
        }
        lap_start_ = tc;
        last_crossing_ = tc;
        armed_ = false;
        since_crossing_ = 0;
      }
    }
  }
  prev_ = position;
  prev_t_ = t;
  return event;
}

}  // namespace fsd
