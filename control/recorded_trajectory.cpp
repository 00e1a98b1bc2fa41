#include "control/recorded_trajectory.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "control/smoothing.hpp"

namespace fsd {

void RecordedTrajectory::record(const VehicleState& state) {
  const Vec2 p = state.pose.position();
  if (!p.allFinite() || !std::isfinite(state.stamp)) return;
  if (!samples_.empty() && (p - samples_.back().p).norm() < config_.sample_spacing) return;
  if (samples_.size() >= static_cast<std::size_t>(std::max(config_.max_samples, 0))) return;
  samples_.push_back({state.stamp, p});
}

namespace {

struct BoundaryCone {
  double s;  // arc length of the cone's foot on the line
  Vec2 p;
};

// Closest point to p on the boundary polyline `b` (sorted by s), among segments whose ends lie within `window` of s
// along the line: a boundary of another stretch of the track that passes nearby is not this one.
std::optional<Vec2> closest_on_boundary(const std::vector<BoundaryCone>& b, const Path& path, double s, const Vec2& p,
                                        double window) {
  if (b.size() < 2) return std::nullopt;
  std::optional<Vec2> best;
  double best_d = std::numeric_limits<double>::infinity();
  const std::size_t n = path.closed ? b.size() : b.size() - 1;
  for (std::size_t i = 0; i < n; ++i) {
    const BoundaryCone& u = b[i];
    const BoundaryCone& v = b[(i + 1) % b.size()];
    if (s_difference(path, s, u.s) > window || s_difference(path, v.s, s) > window) continue;
    const Vec2 d = v.p - u.p;
    const double l2 = d.squaredNorm();
    const double t = l2 > 0 ? std::clamp((p - u.p).dot(d) / l2, 0.0, 1.0) : 0.0;
    const Vec2 q = u.p + t * d;
    if ((q - p).norm() < best_d) best_d = (q - p).norm(), best = q;
  }
  return best;
}

}  // namespace

double recentre_on_cones(Path& path, const std::vector<Cone>& cones, const ColourConvention& convention,
                         double reach) {
  // Each boundary is the polyline through its cones in their order along the line (colour names the side; a cone
  // without one is on the side of the line it stands). The middle is half way between the two polylines, as
  // between the boundaries a driver sees, not between single cones: in a bend with cones 5 m apart the nearest
  // cone across can be well ahead or behind.
  std::vector<BoundaryCone> left, right;
  for (const auto& c : cones) {
    if (!c.position.allFinite()) continue;
    const auto foot = project(path, c.position.head<2>());
    if (!foot || foot->distance() > reach) continue;
    const ConeRole role = convention.role_of(c.colour);
    const bool is_left = role == ConeRole::Left || (role != ConeRole::Right && foot->lateral > 0);
    (is_left ? left : right).push_back({foot->s, c.position.head<2>()});
  }
  auto by_s = [](const BoundaryCone& a, const BoundaryCone& b) { return a.s < b.s; };
  std::sort(left.begin(), left.end(), by_s);
  std::sort(right.begin(), right.end(), by_s);
  double sum = 0;
  std::size_t n = 0;
  std::vector<Vec2> moved(path.points.size());
  for (std::size_t i = 0; i < path.points.size(); ++i) {
    const PathPoint& q = path.points[i];
    moved[i] = q.p;
    const auto l = closest_on_boundary(left, path, q.s, q.p, reach);
    const auto r = closest_on_boundary(right, path, q.s, q.p, reach);
    if (!l || !r || (*l - q.p).norm() > reach || (*r - q.p).norm() > reach) continue;
    moved[i] = 0.5 * (*l + *r);
    sum += (moved[i] - q.p).squaredNorm();
    ++n;
  }
  for (std::size_t i = 0; i < moved.size(); ++i) path.points[i].p = moved[i];
  compute_geometry(path);
  return n ? std::sqrt(sum / static_cast<double>(n)) : 0.0;
}

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
    lap = smooth_path(lap, config_.ds, config_.smoothing_wavelength);
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
  return r;
}

}  // namespace fsd
