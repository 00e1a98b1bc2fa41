#include "localization/loop_closure/loop_solve.hpp"

#include <algorithm>

namespace fsd::loop_closure {

namespace {

Pose2 lerp(const Pose2& a, const Pose2& b, double u) {
  return {a.x + u * (b.x - a.x), a.y + u * (b.y - a.y), wrap_angle(a.yaw + u * wrap_angle(b.yaw - a.yaw))};
}

}  // namespace

Pose2 LoopClosure::correction_at(Stamp when) const {
  if (keyframes.empty() || when < keyframes.front().t) return {};
  auto fix = [](const ClosedKeyframe& k) { return k.optimised * k.estimate.inverse(); };
  if (when >= keyframes.back().t) return fix(keyframes.back());
  const auto hi = std::upper_bound(keyframes.begin(), keyframes.end(), when,
                                   [](Stamp v, const ClosedKeyframe& k) { return v < k.t; });
  const auto lo = hi - 1;
  const double span = hi->t - lo->t;
  return lerp(fix(*lo), fix(*hi), span > 0 ? (when - lo->t) / span : 0.0);
}

LoopSolveResult solve_loop(const LoopSolve& s) {
  LoopSolveResult out;
  const LapGraphResult r = s.graph.optimise();
  if (!r.solved || r.poses.size() != s.estimates.size()) return out;
  out.solved = true;
  LoopClosure& c = out.closure;
  c.t = s.stamps.back();
  c.correction = r.poses.back() * s.estimates.back().inverse();
  c.pairs = s.pairs;
  c.rms = s.rms;
  for (std::size_t k = 0; k < s.estimates.size(); ++k) c.keyframes.push_back({s.stamps[k], s.estimates[k], r.poses[k]});
  for (const Cone& ref : s.reference) {
    Cone m = ref;
    const Vec2 p = r.landmarks.at(int(ref.id));
    m.position = Vec3(p.x(), p.y(), 0.0);
    out.start_scene.push_back(m);
  }
  return out;
}

}  // namespace fsd::loop_closure
