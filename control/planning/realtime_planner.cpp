#include "control/planning/realtime_planner.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>

#include "common/car.hpp"
#include "control/planning/arc_path.hpp"
#include "control/planning/reference_line.hpp"

namespace fsd {

double PathConfig::kappa_lock() const { return kinematic_curvature(max_steer, wheelbase); }

double PathConfig::first_beyond_lock(const Path& path) const {
  const double limit = (1.0 + accept_lock_excess) * kappa_lock();
  for (const auto& q : path.points)
    if (std::abs(q.kappa) > limit) return q.s;
  return std::numeric_limits<double>::infinity();
}

namespace {

int side_of_role(ConeRole r) {
  if (r == ConeRole::Left) return 1;
  if (r == ConeRole::Right) return -1;
  return 0;
}

// The first `length` metres of an open path.
void cut(Path& path, double length) {
  auto& pts = path.points;
  std::size_t keep = 0;
  while (keep < pts.size() && pts[keep].s <= length + 1e-9) ++keep;
  pts.resize(std::max<std::size_t>(keep, 2));
}

std::string describe_short(const SweepResult& s, const std::vector<Obstacle>& obstacles, const Pose2& pose) {
  char buf[160];
  const Vec2 at = s.first_short_obstacle >= 0
                      ? pose.transform(obstacles[static_cast<std::size_t>(s.first_short_obstacle)].p)
                      : Vec2(pose.x, pose.y);
  std::snprintf(buf, sizeof buf,
                "no room for the car %.1f m ahead: its body would come within %.2f m of the cone at "
                "(%.2f, %.2f)",
                s.first_short_s, std::max(0.0, s.min_clearance), at.x(), at.y());
  return buf;
}

}  // namespace

RealtimePlanner::RealtimePlanner(PlannerConfig config, PathConfig path, ColourConvention convention, SpeedLimits limits)
    : config_(config), path_(path), convention_(std::move(convention)), speed_(limits) {}

void RealtimePlanner::set_config(const PlannerConfig& c, const PathConfig& path) {
  config_ = c;
  path_ = path;
}

PlanResult RealtimePlanner::plan(const std::vector<Cone>& cones, const VehicleState& state,
                                 const Path* previous) const {
  PlanResult result;
  const Pose2& pose = state.pose;
  if (!std::isfinite(pose.x) || !std::isfinite(pose.y) || !std::isfinite(pose.yaw)) {
    result.reason = "vehicle pose not finite";
    return result;
  }

  // Cones in the vehicle frame, nearest first, merged when closer than merge_distance: those ahead for the walk,
  // all within range for the body to keep clear of (a path round a tight turn comes back past cones now behind).
  struct Near {
    double d2;
    WalkCone c;
    double radius;
  };
  std::vector<Near> near;
  near.reserve(cones.size());
  for (const Cone& c : cones) {
    if (!c.position.allFinite()) continue;
    const Vec2 local = pose.inverse_transform(c.position.head<2>());
    if (local.squaredNorm() > config_.range * config_.range) continue;
    const int side = config_.walk.use_colours ? side_of_role(convention_.role_of(c.colour)) : 0;
    const double radius = c.colour == ConeColour::BigOrange ? path_.big_cone_radius : path_.cone_radius;
    near.push_back({local.squaredNorm(), {local, side}, radius});
  }
  std::sort(near.begin(), near.end(), [](const Near& a, const Near& b) { return a.d2 < b.d2; });
  std::vector<WalkCone> local;
  std::vector<Obstacle> obstacles;
  for (const auto& n : near) {
    obstacles.push_back({n.c.p, n.radius});
    if (n.c.p.x() < -config_.behind || local.size() >= static_cast<std::size_t>(std::max(config_.max_cones, 3)))
      continue;
    bool merged = false;
    for (auto& l : local)
      if ((l.p - n.c.p).squaredNorm() < config_.merge_distance * config_.merge_distance) {
        if (l.side == 0) l.side = n.c.side;
        merged = true;
        break;
      }
    if (!merged) local.push_back(n.c);
  }
  result.cones_used = static_cast<int>(local.size());

  const CorridorWalk walk = walk_corridor(local, config_.walk);
  result.triangles = walk.triangles;
  result.single_boundary = walk.single_boundary;
  result.ignored_colours = walk.ignored_colours;
  for (const Vec2& m : walk.mids) result.midpoints.push_back(pose.transform(m));
  if (walk.mids.empty()) {
    result.reason = "no gate ahead of the car";
    return result;
  }

  // The reference: from the car along its heading, then the gates' midpoints (those beside the car would kink it).
  const double dn = path_.node_spacing;
  std::vector<Vec2> poly{Vec2::Zero(), Vec2(1.0, 0.0)};
  for (const Vec2& m : walk.mids)
    if (!(m.x() < 1.5 && m.norm() < 2.0)) poly.push_back(m);
  ReferenceLine ref = make_reference(poly, false, dn, config_.reference_wavelength);
  if (ref.nodes.size() < 4) {
    result.reason = "planned corridor too short";
    return result;
  }
  // The path leaves from the car's rear axle along its heading.
  ref.nodes[0] = Vec2::Zero();
  compute_normals(ref);
  const Body& body = path_.body;
  const double inset = body.half_width + path_.cone_radius;
  const Room room = room_between(ref, walk.left, walk.right, false, inset, 6.0, 0.5 * config_.walk.nominal_width);

  OptimizerInput in;
  in.reference = ref.nodes;
  in.normals = ref.normals;
  in.lo = room.lo;
  in.hi = room.hi;
  in.fixed = 1;
  in.start_heading = 0.0;
  // Moving, the path starts on the curvature the car drives now, give or take what its steering can change by the
  // first node at this speed (a car crawling at the lock can unwind in a few centimetres, one at speed cannot); at a
  // standstill the wheels turn before the car moves.
  constexpr double kSteersInPlace = 0.5;  // m/s
  const PathOptimizer optimizer(path_.optimizer, body, path_.kappa_lock());
  // The curvature the car drives is its yaw rate over its speed (at speed it understeers: less than the wheels'
  // angle would give).
  if (state.speed() >= kSteersInPlace && std::isfinite(state.yaw_rate)) {
    in.start_kappa = std::clamp(state.yaw_rate / state.speed(), -optimizer.kappa_max(), optimizer.kappa_max());
    in.start_kappa_slack = speed_.limits().kappa_rate_max * path_.node_spacing / state.speed();
  } else
    in.rate_free_until = config_.free_from;
  in.free_from = config_.free_from;
  in.obstacles = obstacles;
  // Solved from the previous plan where there is one, from the midline where not (or when that did not come out
  // clear): the first clear one, else the one that stays clear the farthest.
  std::vector<std::optional<std::vector<double>>> starts;
  if (previous && previous->points.size() >= 2) {
    std::vector<Vec2> before;
    for (const auto& q : previous->points) before.push_back(pose.inverse_transform(q.p));
    starts.emplace_back(offsets_of(ref, before, 3.0));
  }
  starts.emplace_back(std::nullopt);
  Path p;
  SweepResult sweep;
  double beyond_lock = 0;
  for (const auto& start : starts) {
    const OptimizerOutput opt = optimizer.solve(in, start ? &*start : nullptr);
    result.iterations += opt.iterations;
    if (opt.points.size() < 2) continue;
    Path candidate = arc_path(opt.points, false);
    // The body along the result: the path ends before it would come too near a cone or pass the lock.
    const SweepResult s = sweep_body(candidate, obstacles, body, path_.accept_clearance, 0.05, config_.free_from);
    const double lock = path_.first_beyond_lock(candidate);
    if (p.empty() || std::min(s.first_short_s, lock) > std::min(sweep.first_short_s, beyond_lock)) {
      p = std::move(candidate);
      sweep = s;
      beyond_lock = lock;
    }
    if (!std::isfinite(sweep.first_short_s) && !std::isfinite(beyond_lock)) break;
  }
  if (p.empty()) {
    result.reason = "path optimizer had nothing to work on";
    return result;
  }
  if (std::isfinite(sweep.first_short_s) && sweep.first_short_s <= beyond_lock) {
    result.cut_short = true;
    result.reason = describe_short(sweep, obstacles, pose);
    cut(p, sweep.first_short_s - 0.05);
  } else if (std::isfinite(beyond_lock)) {
    result.cut_short = true;
    result.reason = "no path within the steering's lock " + std::to_string(beyond_lock) + " m ahead";
    cut(p, beyond_lock - 0.05);
  }
  if (p.length() < config_.min_length) {
    if (result.reason.empty()) result.reason = "planned path too short";
    return result;
  }
  result.clearance = sweep_body(p, obstacles, body, 0.0, 0.05, config_.free_from).min_clearance;
  p.stamp = state.stamp;
  transform_path(p, pose);
  // A plan that runs to the end of what is seen stops with its body inside it; one cut short, before the cone.
  if (config_.end_speed > 0)
    speed_.apply(p, state.speed(), config_.end_speed);
  else
    speed_.apply_until(p, state.speed(), result.cut_short ? p.length() : p.length() - body.front);
  result.path = std::move(p);
  result.ok = true;
  return result;
}

}  // namespace fsd
