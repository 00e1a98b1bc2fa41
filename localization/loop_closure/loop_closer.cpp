#include "localization/loop_closure/loop_closer.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>

namespace fsd::loop_closure {

namespace {

constexpr double kNever = -std::numeric_limits<double>::infinity();

bool compatible(ConeColour a, ConeColour b) { return a == b || a == ConeColour::Unknown || b == ConeColour::Unknown; }

ConeColour voted(const std::array<int, 6>& votes) {
  const auto top = std::max_element(votes.begin(), votes.end());
  return *top > 0 ? static_cast<ConeColour>(top - votes.begin()) : ConeColour::Unknown;
}

}  // namespace

Cone LoopCloser::Landmark::cone(int id) const {
  Cone c;
  const Vec2 p = sum / double(std::max(1, n));
  c.position = Vec3(p.x(), p.y(), 0.0);
  c.colour = voted(votes);
  c.id = std::uint32_t(id);
  return c;
}

std::optional<LoopClosure> LoopCloser::add(Stamp t, const Pose2& estimate, const std::vector<Cone>& seen) {
  const auto solve = feed(t, estimate, seen);
  if (!solve) return std::nullopt;
  return finish(solve_loop(*solve));
}

std::optional<LoopSolve> LoopCloser::feed(Stamp t, const Pose2& estimate, const std::vector<Cone>& seen) {
  if (!cfg_.enabled) return std::nullopt;
  if (solving_) {
    held_.push_back({t, estimate, seen});
    return std::nullopt;
  }
  return take(t, estimate, seen, true);
}

std::optional<LoopClosure> LoopCloser::finish(const LoopSolveResult& r) {
  if (!solving_) return std::nullopt;
  solving_ = false;
  std::vector<Frame> held = std::move(held_);
  held_.clear();
  std::optional<LoopClosure> out;
  if (r.solved) {
    out = r.closure;
    out->lap = ++laps_closed_;
    if (start_scene_.empty()) start_scene_ = r.start_scene;
    const Pose2& end = out->keyframes.back().optimised;
    last_pose_ = end;
    start_lap(out->t, end);
  }
  // Not closing again here: the next lap is too short for it, and after a failure the next live keyframe tries.
  for (const Frame& f : held) take(f.t, out ? out->correction * f.estimate : f.estimate, f.seen, false);
  return out;
}

std::optional<LoopSolve> LoopCloser::take(Stamp t, const Pose2& estimate, const std::vector<Cone>& seen,
                                          bool may_close) {
  if (!start_pose_) {
    start_pose_ = last_pose_ = estimate;
    start_lap(t, estimate);
    observe(0, estimate, seen);
    return std::nullopt;
  }
  if (t <= stamps_.back()) return std::nullopt;
  odometer_ += (estimate.position() - last_pose_->position()).norm();
  last_pose_ = estimate;
  if ((estimate.position() - estimates_.back().position()).norm() < cfg_.keyframe_spacing) return std::nullopt;
  const int k = graph_.add_keyframe(t, estimate);
  estimates_.push_back(estimate);
  stamps_.push_back(t);
  observe(k, estimate, seen);
  return may_close ? try_close() : std::nullopt;
}

void LoopCloser::start_lap(Stamp t, const Pose2& pose) {
  graph_ = LapGraph(cfg_.graph);
  landmarks_.clear();
  estimates_ = {pose};
  stamps_ = {t};
  lap_start_odometer_ = odometer_;
  graph_.add_keyframe(t, pose);
  // After the first loop the start's scene is known in the map frame: held by the lap's first keyframe (itself
  // held), it is what the next loop closes against. It takes no sightings: the cones seen now are new landmarks.
  for (const Cone& c : start_scene_) {
    Landmark l;
    l.sum = c.position.head<2>();
    l.n = 1;
    l.first_seen = l.last_seen = kNever;
    l.votes[std::size_t(c.colour)] = 1;
    l.reference = true;
    graph_.observe(0, int(landmarks_.size()), pose.inverse_transform(l.sum), cfg_.sighting_sigma);
    landmarks_.push_back(l);
  }
}

void LoopCloser::observe(int k, const Pose2& pose, const std::vector<Cone>& seen) {
  struct Placed {
    Vec2 v, p;
    ConeColour colour;
  };
  std::vector<Placed> placed;
  for (const Cone& c : seen) {
    const Vec2 v = c.position.head<2>();
    if (!v.allFinite() || v.norm() > cfg_.max_range) continue;
    placed.push_back({v, pose.transform(v), c.colour});
  }
  // One frame's sightings are distinct cones: nearest pairs first, each landmark taking at most one.
  std::vector<std::tuple<double, std::size_t, std::size_t>> pairs;
  for (std::size_t i = 0; i < placed.size(); ++i)
    for (std::size_t j = 0; j < landmarks_.size(); ++j) {
      const Landmark& l = landmarks_[j];
      if (odometer_ - l.last_seen > cfg_.live_distance || !compatible(placed[i].colour, voted(l.votes))) continue;
      const double d = (l.sum / double(l.n) - placed[i].p).norm();
      if (d < cfg_.association_gate) pairs.emplace_back(d, i, j);
    }
  std::sort(pairs.begin(), pairs.end());
  constexpr std::size_t kNone = std::numeric_limits<std::size_t>::max();
  std::vector<std::size_t> of(placed.size(), kNone);
  std::vector<char> taken(landmarks_.size(), 0);
  for (const auto& [d, i, j] : pairs) {
    if (of[i] != kNone || taken[j]) continue;
    of[i] = j;
    taken[j] = 1;
  }
  const bool starting = laps_closed_ == 0 && odometer_ - lap_start_odometer_ <= cfg_.start_distance;
  for (std::size_t i = 0; i < placed.size(); ++i) {
    if (of[i] == kNone) {
      of[i] = landmarks_.size();
      Landmark& l = landmarks_.emplace_back();
      l.first_seen = odometer_;
      l.reference = starting;
    }
    Landmark& l = landmarks_[of[i]];
    l.sum += placed[i].p;
    ++l.n;
    l.last_seen = odometer_;
    if (placed[i].colour != ConeColour::Unknown) ++l.votes[std::size_t(placed[i].colour)];
    graph_.observe(k, int(of[i]), placed[i].v, cfg_.sighting_sigma);
  }
}

std::optional<LoopSolve> LoopCloser::try_close() {
  if (lap_distance() < cfg_.min_lap_distance) return std::nullopt;
  if ((estimates_.back().position() - start_pose_->position()).norm() > cfg_.near_start) return std::nullopt;
  std::vector<Cone> current, reference;
  for (std::size_t id = 0; id < landmarks_.size(); ++id) {
    const Landmark& l = landmarks_[id];
    if (l.reference) {
      if (l.n >= cfg_.min_sightings || l.first_seen == kNever) reference.push_back(l.cone(int(id)));
    } else if (l.n >= cfg_.min_sightings && odometer_ - l.last_seen <= cfg_.recent_distance &&
               l.first_seen - lap_start_odometer_ > cfg_.start_distance) {
      current.push_back(l.cone(int(id)));
    }
  }
  const auto a = align_cones(current, reference, cfg_.alignment);
  if (!a) return std::nullopt;
  // The lap's graph stays as it is: after a failed solve the next keyframe tries again.
  LoopSolve s{.graph = graph_,
              .stamps = stamps_,
              .estimates = estimates_,
              .reference = reference,
              .pairs = int(a->pairs.size()),
              .rms = a->rms};
  for (const auto& [i, j] : a->pairs)
    s.graph.same_cone(int(current[std::size_t(i)].id), int(reference[std::size_t(j)].id));
  solving_ = true;
  return s;
}

}  // namespace fsd::loop_closure
