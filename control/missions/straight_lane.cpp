#include "control/missions/straight_lane.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

namespace fsd {
namespace {

// Two parallel rows: the centre line through `centre` along `dir`, the rows `half_width` either side.
struct Rows {
  Vec2 centre, dir;
  double half_width = 0;
};

// The cones within `tol` of a row, and on which side (+1 left of the centre line, −1 right).
struct RowMembers {
  std::vector<int> index;
  std::vector<double> side;
  int left = 0, right = 0;
};

RowMembers members(const std::vector<Vec2>& pts, const Rows& rows, double tol) {
  RowMembers m;
  const Vec2 left(-rows.dir.y(), rows.dir.x());
  for (int k = 0; k < static_cast<int>(pts.size()); ++k) {
    const double y = (pts[k] - rows.centre).dot(left);
    if (std::abs(std::abs(y) - rows.half_width) > tol) continue;
    m.index.push_back(k);
    m.side.push_back(y > 0 ? 1.0 : -1.0);
    ++(y > 0 ? m.left : m.right);
  }
  return m;
}

// Least squares over the rows' cones: offset y = a + b·s + side·w in the frame of `rows` (one direction, one width).
std::optional<Rows> refit(const std::vector<Vec2>& pts, const Rows& rows, const RowMembers& m) {
  const Vec2 left(-rows.dir.y(), rows.dir.x());
  Eigen::MatrixXd A(m.index.size(), 3);
  Eigen::VectorXd y(m.index.size());
  for (std::size_t r = 0; r < m.index.size(); ++r) {
    const Vec2 d = pts[m.index[r]] - rows.centre;
    A.row(r) << 1.0, d.dot(rows.dir), m.side[r];
    y(r) = d.dot(left);
  }
  const Eigen::Vector3d x = A.colPivHouseholderQr().solve(y);
  if (!x.allFinite() || x(2) <= 0) return std::nullopt;
  Rows out;
  out.dir = (rows.dir + x(1) * left).normalized();
  out.centre = rows.centre + x(0) * left;
  out.half_width = x(2);
  return out;
}

}  // namespace

std::optional<Path> straight_from_cones(const std::vector<Cone>& cones, const Pose2& start, double length, double ds,
                                        const StraightLaneConfig& cfg) {
  const Vec2 origin = start.position(), heading(std::cos(start.yaw), std::sin(start.yaw));
  const Vec2 heading_left(-heading.y(), heading.x());
  std::vector<Vec2> pts;
  for (const auto& c : cones) {
    if (!c.position.allFinite()) continue;
    const Vec2 m = c.position.head<2>();
    if ((m - origin).dot(heading) < -cfg.behind || std::abs((m - origin).dot(heading_left)) > cfg.reach) continue;
    pts.push_back(m);
  }
  const int n = static_cast<int>(pts.size());
  if (n < 2 * cfg.min_row_cones) return std::nullopt;

  // Consensus: each pair of cones far enough apart proposes a row through both; the other row is the parallel
  // offset (a lane's width away) that most cones share. The proposal most cones agree with wins.
  const double tol = cfg.row_tolerance, cos_max = std::cos(cfg.max_angle);
  int best_score = 0;
  Rows best;
  std::vector<double> offsets;
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j) {
      Vec2 d = pts[j] - pts[i];
      const double len = d.norm();
      if (len < 3.0) continue;  // too short a base for a direction
      d /= len;
      if (d.dot(heading) < 0) d = -d;
      if (d.dot(heading) < cos_max) continue;
      const Vec2 left(-d.y(), d.x());
      int on_row = 0;
      offsets.clear();
      for (const auto& p : pts) {
        const double y = (p - pts[i]).dot(left);
        if (std::abs(y) <= tol)
          ++on_row;
        else if (std::abs(y) >= cfg.min_width - tol && std::abs(y) <= cfg.max_width + tol)
          offsets.push_back(y);
      }
      if (on_row < cfg.min_row_cones || static_cast<int>(offsets.size()) < cfg.min_row_cones) continue;
      std::sort(offsets.begin(), offsets.end());
      int other = 0;
      double other_offset = 0;
      for (std::size_t lo = 0, hi = 0; lo < offsets.size(); ++lo) {
        while (hi < offsets.size() && offsets[hi] - offsets[lo] <= 2 * tol) ++hi;
        if (static_cast<int>(hi - lo) > other) {
          other = static_cast<int>(hi - lo);
          other_offset = 0.5 * (offsets[lo] + offsets[hi - 1]);
        }
      }
      if (other < cfg.min_row_cones || on_row + other <= best_score) continue;
      best_score = on_row + other;
      best.dir = d;
      best.centre = pts[i] + 0.5 * other_offset * left;
      best.half_width = 0.5 * std::abs(other_offset);
    }
  if (best_score == 0) return std::nullopt;

  // Least squares over the agreeing cones, twice: the refined line takes in cones at the far end that a line
  // through two near cones missed by a few centimetres.
  Rows rows = best;
  for (int round = 0; round < 2; ++round) {
    const RowMembers m = members(pts, rows, tol);
    if (m.left < cfg.min_row_cones || m.right < cfg.min_row_cones) break;
    const auto fitted = refit(pts, rows, m);
    if (!fitted || 2 * fitted->half_width < cfg.min_width - 2 * tol || 2 * fitted->half_width > cfg.max_width + 2 * tol)
      break;
    rows = *fitted;
  }

  const double s0 = (origin - rows.centre).dot(rows.dir);
  Path p;
  for (double s = 0; s <= length + 1e-9; s += ds) p.points.push_back({rows.centre + (s0 + s) * rows.dir, 0, 0, 0, 0});
  compute_geometry(p);
  return p;
}

}  // namespace fsd
