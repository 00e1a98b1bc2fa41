#include "drivers/sim/world/reference_line.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace fsd::sim {

namespace {

// 2-opt: reverses stretches while that shortens the chain (closed: the loop through every cone; open: the path
// from the first cone, whose far end is free). A greedy chain jumps where the other side of a narrow loop's island
// is nearer than the next cone (amz_fssim_thin: a 14 m jump that skips five cones); the shortest loop through a
// boundary's cones is the boundary. The first cone stays first.
void untangle(std::vector<Vec2>& c, bool closed) {
  const std::size_t n = c.size();
  if (n < 5) return;
  for (bool improved = true; improved;) {
    improved = false;
    for (std::size_t i = 1; i + 1 < n; ++i)
      for (std::size_t j = i + 1; j < n; ++j) {
        const Vec2 &a = c[i - 1], &b = c[i], &d = c[j];
        double gain;
        if (j + 1 < n || closed) {
          const Vec2& e = c[(j + 1) % n];
          if ((j + 1) % n == i - 1) continue;  // the two edges share a cone
          gain = (a - b).norm() + (d - e).norm() - (a - d).norm() - (b - e).norm();
        } else {
          gain = (a - b).norm() - (a - d).norm();  // the open chain's tail turned round
        }
        if (gain > 1e-9) {
          std::reverse(c.begin() + static_cast<long>(i), c.begin() + static_cast<long>(j) + 1);
          improved = true;
        }
      }
  }
}

double chain_length(const std::vector<Vec2>& c, bool closed) {
  double l = closed && c.size() > 1 ? (c.front() - c.back()).norm() : 0.0;
  for (std::size_t i = 1; i < c.size(); ++i) l += (c[i] - c[i - 1]).norm();
  return l;
}

// The median step of a chain (closed: with the edge from its end back to its beginning).
double median_step(const std::vector<Vec2>& c, bool closed) {
  std::vector<double> steps;
  if (closed) steps.push_back((c.front() - c.back()).norm());
  for (std::size_t i = 1; i < c.size(); ++i) steps.push_back((c[i] - c[i - 1]).norm());
  std::nth_element(steps.begin(), steps.begin() + static_cast<long>(steps.size() / 2), steps.end());
  return steps[steps.size() / 2];
}

// A cone gap or two at a boundary's cone spacing: the most a loop's closing edge, or a line's widest step, may be.
double gap_bound(double spacing) { return std::max(6.0, 2.75 * spacing); }

// The cones as the file lists them when that is a line: every step at most a cone gap, the ends far apart. An
// open course staged on its first straight has cones behind the car, where a chain grown from the cone beside it
// runs to the finish and jumps back; and where two parts of it run a cone gap apart, no shortest path is the
// boundary. Files list a boundary in order (generated layouts and most published ones do). Runs in the driving
// direction (the start heading, at the cone nearest the start). Empty when the listed order is no such line.
std::vector<Vec2> listed_line(std::vector<Vec2> pts, const Pose2& start) {
  if (pts.size() < 5) return {};
  double widest = 0;
  for (std::size_t i = 1; i < pts.size(); ++i) widest = std::max(widest, (pts[i] - pts[i - 1]).norm());
  const double gap = gap_bound(median_step(pts, false));
  if (widest > gap || (pts.front() - pts.back()).norm() <= gap) return {};
  const Vec2 s = start.position();
  std::size_t near = 0;
  for (std::size_t i = 1; i < pts.size(); ++i)
    if ((pts[i] - s).norm() < (pts[near] - s).norm()) near = i;
  const Vec2 along = near + 1 < pts.size() ? pts[near + 1] - pts[near] : pts[near] - pts[near - 1];
  if (along.dot(Vec2(std::cos(start.yaw), std::sin(start.yaw))) < 0) std::reverse(pts.begin(), pts.end());
  return pts;
}

// Orders cones into a boundary polyline: the listed order when it is a line (above); else start at the cone
// nearest the start pose (ahead or beside it), then repeatedly the nearest unvisited cone; a boundary whose ends
// are close is a loop, and is untangled.
std::vector<Vec2> chain(std::vector<Vec2> pts, const Pose2& start, bool& closed) {
  std::vector<Vec2> out = listed_line(pts, start);
  closed = false;
  if (!out.empty() || pts.empty()) return out;
  const Vec2 s = start.position();
  const Vec2 fwd(std::cos(start.yaw), std::sin(start.yaw));
  std::size_t first = 0;
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const Vec2 d = pts[i] - s;
    // Prefer cones beside or just ahead of the car: penalise those behind it.
    const double cost = d.norm() + (d.dot(fwd) < -1.0 ? 100.0 : 0.0);
    if (cost < best) best = cost, first = i;
  }
  std::vector<bool> used(pts.size(), false);
  out.push_back(pts[first]);
  used[first] = true;
  // First step goes forwards along the start heading so the loop runs the driving direction.
  for (std::size_t n = 1; n < pts.size(); ++n) {
    const Vec2& cur = out.back();
    std::size_t pick = pts.size();
    double pick_cost = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < pts.size(); ++i) {
      if (used[i]) continue;
      const Vec2 d = pts[i] - cur;
      double cost = d.norm();
      if (n == 1 && d.dot(fwd) < 0) cost += 1000.0;
      if (cost < pick_cost) pick_cost = cost, pick = i;
    }
    used[pick] = true;
    out.push_back(pts[pick]);
  }
  double max_step = 0;
  for (std::size_t i = 1; i < out.size(); ++i) max_step = std::max(max_step, (out[i] - out[i - 1]).norm());
  closed = out.size() > 3 && (out.front() - out.back()).norm() <= std::max(6.0, 1.5 * max_step);
  if (closed) {
    untangle(out, true);
  } else if (out.size() >= 5) {
    // The greedy chain can end far from its start on a loop too: where two legs of the loop run side by side a
    // couple of metres apart it jumps across, and the cones it skipped come last. A boundary is a loop when its
    // shortest loop is longer than its shortest open chain by a cone spacing or two; on a line, by the line.
    std::vector<Vec2> loop = out, line = out;
    untangle(loop, true);
    untangle(line, false);
    // 2-opt from a tangled chain can stop at a loop that still detours; files usually list a boundary's cones in
    // order along it (generated layouts and most published ones do), so that order, from the same first cone, is
    // a second start: the shorter loop wins.
    std::vector<Vec2> listed(pts.begin() + static_cast<long>(first), pts.end());
    listed.insert(listed.end(), pts.begin(), pts.begin() + static_cast<long>(first));
    untangle(listed, true);
    if (chain_length(listed, true) < chain_length(loop, true)) loop = std::move(listed);
    const double spacing = median_step(loop, true);  // the median: a line's loop has one edge as long as the line
    // A loop's shortest open chain may cut across an island once (two cone steps saved for one short jump): on
    // the generated loops the difference is at most 2.5 cone spacings; the shared open layouts' are 3.2 (epfl_VSV,
    // a U) and 13 (acceleration).
    closed = chain_length(loop, true) - chain_length(line, false) <= gap_bound(spacing);
    if (closed) out = std::move(loop);
  }
  if (closed) {
    if ((out[1] - out[0]).dot(fwd) < 0) std::reverse(out.begin() + 1, out.end());  // the driving direction
  }
  return out;
}

std::vector<Vec2> resample(const std::vector<Vec2>& poly, bool closed, double spacing) {
  std::vector<Vec2> out;
  if (poly.size() < 2) return poly;
  std::vector<Vec2> p = poly;
  if (closed) p.push_back(poly.front());
  for (std::size_t i = 1; i < p.size(); ++i) {
    const Vec2 a = p[i - 1], b = p[i];
    const double len = (b - a).norm();
    const int n = std::max(1, static_cast<int>(std::ceil(len / spacing)));
    for (int k = 0; k < n; ++k) out.push_back(a + (b - a) * (static_cast<double>(k) / n));
  }
  if (!closed) out.push_back(p.back());
  return out;
}

double point_segment_distance(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 ab = b - a;
  const double l2 = ab.squaredNorm();
  const double t = l2 > 0 ? std::clamp((p - a).dot(ab) / l2, 0.0, 1.0) : 0.0;
  return (p - (a + t * ab)).norm();
}

Vec2 closest_on(const std::vector<Vec2>& poly, bool closed, const Vec2& p) {
  Vec2 best = poly.front();
  double bd = std::numeric_limits<double>::infinity();
  const std::size_t n = poly.size();
  const std::size_t segs = closed ? n : n - 1;
  for (std::size_t i = 0; i < segs; ++i) {
    const Vec2 a = poly[i], b = poly[(i + 1) % n];
    const Vec2 ab = b - a;
    const double l2 = ab.squaredNorm();
    const double t = l2 > 0 ? std::clamp((p - a).dot(ab) / l2, 0.0, 1.0) : 0.0;
    const Vec2 q = a + t * ab;
    const double d = (p - q).squaredNorm();
    if (d < bd) bd = d, best = q;
  }
  return best;
}

}  // namespace

ReferenceLine::ReferenceLine(const Track& track, double spacing) {
  std::vector<Vec2> l, r;
  for (const auto& c : track.cones) {
    if (c.role == ConeRole::Left) l.push_back(c.position);
    if (c.role == ConeRole::Right) r.push_back(c.position);
  }
  bool lc = false, rc = false;
  left_ = chain(l, track.start, lc);
  right_ = chain(r, track.start, rc);
  closed_ = lc && rc;
  if (left_.size() < 2 || right_.size() < 2) return;
  const auto ls = resample(left_, closed_, spacing);
  for (const auto& p : ls) centre_.push_back(0.5 * (p + closest_on(right_, closed_, p)));
  if (!closed_ && centre_.size() >= 2) {
    // An open track (acceleration) starts behind its first cones and ends in a braking zone past its last ones:
    // extend the line back to the start pose (when the car stands before its beginning) and straight on beyond
    // the end.
    const Vec2 s = track.start.position();
    if ((s - centre_.front()).norm() > spacing && (centre_[1] - centre_[0]).dot(centre_.front() - s) > 0) {
      const Vec2 step = (centre_.front() - s) / std::ceil((centre_.front() - s).norm() / spacing);
      std::vector<Vec2> head;
      for (Vec2 q = s; (q - centre_.front()).norm() > 0.5 * spacing; q += step) head.push_back(q);
      centre_.insert(centre_.begin(), head.begin(), head.end());
    }
    const Vec2 dir = (centre_.back() - centre_[centre_.size() - 2]).normalized();
    const Vec2 end = centre_.back();
    for (double d = spacing; d <= 100.0; d += spacing) centre_.push_back(end + d * dir);
  }
  for (std::size_t i = 1; i < centre_.size(); ++i) length_ += (centre_[i] - centre_[i - 1]).norm();
  if (closed_ && centre_.size() > 1) length_ += (centre_.front() - centre_.back()).norm();
}

double ReferenceLine::distance(const Vec2& p) const {
  if (centre_.empty()) return std::numeric_limits<double>::infinity();
  if (centre_.size() == 1) return (p - centre_[0]).norm();
  double best = std::numeric_limits<double>::infinity();
  const std::size_t n = centre_.size();
  const std::size_t segs = closed_ ? n : n - 1;
  for (std::size_t i = 0; i < segs; ++i)
    best = std::min(best, point_segment_distance(p, centre_[i], centre_[(i + 1) % n]));
  return best;
}

}  // namespace fsd::sim
