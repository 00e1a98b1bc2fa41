#include "control/recorded_trajectory.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "control/corridor.hpp"
#include "control/racing_line.hpp"
#include "control/smoothing.hpp"

namespace fsd {

void RecordedTrajectory::record(const VehicleState& state) {
  const Vec2 p = state.pose.position();
  if (!p.allFinite() || !std::isfinite(state.stamp)) return;
  if (!samples_.empty() && (p - samples_.back().p).norm() < config_.sample_spacing) return;
  if (samples_.size() >= static_cast<std::size_t>(std::max(config_.max_samples, 0))) return;
  samples_.push_back({state.stamp, p});
}

double RecordedTrajectory::relocate(const std::function<Pose2(Stamp)>& correction) {
  double moved = 0;
  for (auto& s : samples_) {
    const Vec2 p = correction(s.t).transform(s.p);
    moved = std::max(moved, (p - s.p).norm());
    s.p = p;
  }
  return moved;
}

double recentre_on_cones(Path& path, const std::vector<Cone>& cones, const ColourConvention& convention, double reach) {
  // Each boundary is the polyline through its cones in their order along the line.
  const Corridor corridor = corridor_along(path, cones, convention, reach);
  const auto& left = corridor.left;
  const auto& right = corridor.right;
  // The centre line: every point of the left boundary (each 0.25 m) and its closest point on the right one, half
  // way between. Built from the boundaries, not from the driven line: in a bend whose inner boundary turns at a
  // single cone, the middle of the driven line's nearest boundary points lies off the corridor's middle.
  std::vector<BoundaryCone> centre;
  if (left.size() >= 2 && right.size() >= 2) {
    constexpr double kStep = 0.25;
    const std::size_t segments = path.closed ? left.size() : left.size() - 1;
    for (std::size_t i = 0; i < segments; ++i) {
      const BoundaryCone& u = left[i];
      const BoundaryCone& v = left[(i + 1) % left.size()];
      const double span = s_difference(path, u.s, v.s);
      if (span < 0 || span > kMaxSpanInReach * reach) continue;  // not neighbours along the line
      const int k = std::max(1, static_cast<int>(std::ceil((v.p - u.p).norm() / kStep)));
      for (int j = 0; j < k; ++j) {
        const double f = static_cast<double>(j) / k;
        const Vec2 a = u.p + f * (v.p - u.p);
        const double sa = u.s + f * span;
        const auto b = closest_on_boundary(right, path, sa, a, reach);
        if (b && (*b - a).norm() <= 2 * reach) centre.push_back({sa, 0.5 * (a + *b)});
      }
    }
  }
  double sum = 0;
  std::size_t n = 0;
  for (auto& q : path.points) {
    const auto m = closest_on_boundary(centre, path, q.s, q.p, reach);
    if (!m || (*m - q.p).norm() > reach) continue;
    sum += (*m - q.p).squaredNorm();
    ++n;
    q.p = *m;
  }
  compute_geometry(path);
  return n ? std::sqrt(sum / static_cast<double>(n)) : 0.0;
}

namespace {
constexpr double kRacingRippleWavelength = 3.0;  // m
constexpr double kRacingRippleRadius = 0.05;     // m
}  // namespace

TrajectoryResult RecordedTrajectory::build(Stamp t0, Stamp t1, const std::vector<Cone>& map_cones,
                                           const ColourConvention& convention, const SpeedProfile& speed,
                                           const std::vector<Vec2>& ahead) const {
  TrajectoryResult r;
  Path raw;
  raw.closed = true;
  raw.stamp = t1;
  for (const auto& s : samples_)
    if (s.t >= t0 && s.t <= t1) raw.points.push_back({s.p, 0, 0, 0, 0});
  for (const auto& q : ahead)
    if (q.allFinite() && (raw.points.empty() || (q - raw.points.back().p).norm() >= config_.sample_spacing))
      raw.points.push_back({q, 0, 0, 0, 0});
  if (raw.points.size() < 10) {
    r.reason = "too few recorded poses for a lap (" + std::to_string(raw.points.size()) + ")";
    return r;
  }
  // Close the loop where the end comes nearest the start: poses driven past the start would double back.
  auto& pts = raw.points;
  std::size_t cut = pts.size() - 1;
  for (std::size_t i = pts.size() - 1; i > pts.size() * 4 / 5; --i)
    if ((pts[i].p - pts.front().p).norm() < (pts[cut].p - pts.front().p).norm()) cut = i;
  if ((pts[cut].p - pts.front().p).norm() < 0.5 * config_.sample_spacing && cut > 0) --cut;
  pts.resize(cut + 1);
  r.closure_gap = (pts.back().p - pts.front().p).norm();
  compute_geometry(raw);
  if (r.closure_gap > config_.max_closure_gap) {
    r.reason = "recorded lap does not close: end " + std::to_string(r.closure_gap) + " m from its start";
    return r;
  }
  if (raw.length() < config_.min_lap_length) {
    r.reason = "recorded lap too short (" + std::to_string(raw.length()) + " m)";
    return r;
  }
  Path lap = smooth_path(raw, config_.ds, config_.smoothing_wavelength);
  if (config_.recentre && !map_cones.empty()) {
    r.recentre_rms = recentre_on_cones(lap, map_cones, convention, config_.recentre_reach);
    // Smoothed again, but never further than max_centre_offset from the centre line: a smoother cuts a corner of
    // the corridor's middle (a hairpin's, or where the middle kinks at a boundary's corner cone) by as much as the
    // bend is sharp.
    lap = smooth_path(lap, config_.ds, config_.smoothing_wavelength, config_.max_centre_offset);
    if (config_.line == "min_curvature") {
      // The room either side: to each boundary's cone line, less the keep (a point without a boundary found
      // near it stays where it is on that side).
      const Corridor corridor = corridor_along(lap, map_cones, convention, config_.recentre_reach);
      std::vector<double> room_left, room_right;
      room_left.reserve(lap.points.size());
      room_right.reserve(lap.points.size());
      for (const auto& q : lap.points) {
        const auto on_left = closest_on_boundary(corridor.left, lap, q.s, q.p, config_.recentre_reach);
        const auto on_right = closest_on_boundary(corridor.right, lap, q.s, q.p, config_.recentre_reach);
        room_left.push_back(on_left ? std::max(0.0, (*on_left - q.p).norm() - config_.racing_keep) : 0.0);
        room_right.push_back(on_right ? std::max(0.0, (*on_right - q.p).norm() - config_.racing_keep) : 0.0);
      }
      auto racing = minimum_curvature_line(lap, room_left, room_right);
      r.racing_offset = racing.max_offset;
      // The line follows the boundaries' polygons where it touches them, a few millimetres of ripple that the
      // curvature (and so the speed profile) would feel: smoothed over a few metres, within 5 cm of its place.
      lap = smooth_path(racing.path, config_.ds, kRacingRippleWavelength, kRacingRippleRadius);
    }
  }
  // Smoothing cuts a hairpin tighter than the steering can turn: there the lap gets the line lap 1's planner gave,
  // at that line's speed cap.
  std::vector<SpeedZone> zones;
  if (!map_cones.empty()) {
    std::vector<Vec2> positions;
    for (const auto& c : map_cones)
      if (c.position.allFinite()) positions.push_back(c.position.head<2>());
    for (const auto& turn : shape_tight_turns_on_lap(lap, positions, config_.tight_turn))
      zones.push_back({turn.s_begin, turn.s_end, config_.tight_turn.v_max});
  }
  speed.apply(lap, 0, 0, zones);
  lap.stamp = t1;
  r.path = std::move(lap);
  r.zones = std::move(zones);
  return r;
}

}  // namespace fsd
