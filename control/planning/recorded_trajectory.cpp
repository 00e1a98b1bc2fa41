#include "control/planning/recorded_trajectory.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "control/planning/arc_path.hpp"
#include "control/planning/corridor.hpp"
#include "control/planning/path_optimizer.hpp"
#include "control/planning/reference_line.hpp"
#include "control/planning/smoothing.hpp"

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
// The centre line's kinks at the boundaries' corner cones are smoothed over this before it is the optimizer's
// reference (the optimizer then finds the line; the reference only carries the normals), and over the others in turn
// when the line it gives is not clear.
constexpr double kReferenceWavelengths[] = {3.0, 6.0, 1.5};  // m
// How far off the centre line the "min_curvature" line may go for a metre's worth of curvature cost: the centre
// weight it uses instead of control.path.w_centre.
constexpr double kMinCurvatureCentreWeight = 0.01;

std::vector<Vec2> points_of(const std::vector<BoundaryCone>& b) {
  std::vector<Vec2> out;
  out.reserve(b.size());
  for (const auto& c : b) out.push_back(c.p);
  return out;
}
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
  if (config_.recentre && !map_cones.empty())
    r.recentre_rms = recentre_on_cones(lap, map_cones, convention, config_.recentre_reach);
  lap = line_through(lap, map_cones, convention, r);
  if (!r.reason.empty()) return r;
  speed.apply(lap, 0, 0);
  lap.stamp = t1;
  r.path = std::move(lap);
  return r;
}

Path RecordedTrajectory::line_through(const Path& centre, const std::vector<Cone>& map_cones,
                                      const ColourConvention& convention, TrajectoryResult& r) const {
  const PathConfig& pc = config_.path;
  std::vector<Vec2> centre_points;
  for (const auto& q : centre.points) centre_points.push_back(q.p);
  const Corridor corridor = corridor_along(centre, map_cones, convention, config_.recentre_reach);
  const Body& body = pc.body;
  const std::vector<Obstacle> obstacles = obstacles_of(map_cones, pc.cone_radius, pc.big_cone_radius);
  PathOptimizerConfig oc = pc.optimizer;
  if (config_.line == "min_curvature") oc.w_centre = kMinCurvatureCentreWeight;
  const PathOptimizer optimizer(oc, body, pc.kappa_lock());
  // The optimizer is a local method: a reference smoothed otherwise starts it elsewhere. The first line that comes
  // out clear of the cones is kept; none clear, the lap is refused.
  Path best;
  SweepResult best_sweep;
  for (const double wavelength : kReferenceWavelengths) {
    const ReferenceLine ref = make_reference(centre_points, true, pc.node_spacing, wavelength);
    const Room room = room_between(ref, points_of(corridor.left), points_of(corridor.right), true,
                                   body.half_width + pc.cone_radius, config_.recentre_reach, 1.5);
    OptimizerInput in;
    in.reference = ref.nodes;
    in.normals = ref.normals;
    in.lo = room.lo;
    in.hi = room.hi;
    in.closed = true;
    in.obstacles = obstacles;
    const OptimizerOutput opt = optimizer.solve(in);
    r.iterations += opt.iterations;
    if (opt.points.size() < 4) continue;
    Path line = arc_path(opt.points, true);
    const SweepResult sweep = sweep_body(line, obstacles, body, pc.accept_clearance, 0.05);
    const double beyond_lock = pc.first_beyond_lock(line);
    const bool clear = !std::isfinite(sweep.first_short_s) && !std::isfinite(beyond_lock);
    if (best.empty() || clear) {
      best = std::move(line);
      best_sweep = sweep;
      r.max_offset = 0;
      for (const double a : opt.alpha) r.max_offset = std::max(r.max_offset, std::abs(a));
    }
    if (clear) {
      r.reason.clear();
      r.clearance = sweep.min_clearance;
      return best;
    }
    char buf[200];
    if (std::isfinite(sweep.first_short_s)) {
      const Vec2 at = obstacles[static_cast<std::size_t>(sweep.first_short_obstacle)].p;
      std::snprintf(buf, sizeof buf,
                    "lap line not clear of the cones: the body comes within %.2f m of the cone at (%.2f, %.2f), "
                    "%.1f m round the lap",
                    sweep.min_clearance, at.x(), at.y(), sweep.first_short_s);
    } else {
      std::snprintf(buf, sizeof buf, "lap line beyond the steering's lock %.1f m round the lap", beyond_lock);
    }
    r.reason = buf;
  }
  if (best.empty()) r.reason = "lap line: too few nodes";
  r.clearance = best_sweep.min_clearance;
  return best.empty() ? centre : best;
}

}  // namespace fsd
