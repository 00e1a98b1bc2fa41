#include "control/recorded_trajectory.hpp"

#include <algorithm>
#include <cmath>

#include "control/smoothing.hpp"

namespace fsd {

void RecordedTrajectory::record(const VehicleState& state) {
  const Vec2 p = state.pose.position();
  if (!p.allFinite() || !std::isfinite(state.stamp)) return;
  if (!samples_.empty() && (p - samples_.back().p).norm() < config_.sample_spacing) return;
  if (samples_.size() >= static_cast<std::size_t>(std::max(config_.max_samples, 0))) return;
  samples_.push_back({state.stamp, p});
}

double recentre_on_cones(Path& path, const std::vector<Cone>& cones, const ColourConvention& convention,
                         double reach) {
  double sum = 0;
  std::size_t n = 0;
  std::vector<Vec2> moved(path.points.size());
  for (std::size_t i = 0; i < path.points.size(); ++i) {
    const PathPoint& q = path.points[i];
    const Vec2 t(std::cos(q.yaw), std::sin(q.yaw)), left(-t.y(), t.x());
    // Nearest cone on each side, by lateral offset, among cones within reach along the line.
    double best_left = reach, best_right = -reach;
    bool have_left = false, have_right = false;
    for (const auto& c : cones) {
      if (!c.position.allFinite()) continue;
      const Vec2 d = c.position.head<2>() - q.p;
      if (std::abs(d.dot(t)) > 0.5 * reach) continue;
      const double lat = d.dot(left);
      const ConeRole role = convention.role_of(c.colour);
      // Colour decides the side when it names one; otherwise the side the cone is on.
      const bool is_left = role == ConeRole::Left || (role != ConeRole::Right && lat > 0);
      if (is_left && lat > 0 && lat < best_left) {
        best_left = lat;
        have_left = true;
      } else if (!is_left && lat < 0 && lat > best_right) {
        best_right = lat;
        have_right = true;
      }
    }
    moved[i] = q.p;
    if (have_left && have_right) {
      const double shift = 0.5 * (best_left + best_right);
      moved[i] = q.p + shift * left;
      sum += shift * shift;
      ++n;
    }
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
  speed.apply(lap, 0, 0);
  lap.stamp = t1;
  r.path = std::move(lap);
  return r;
}

}  // namespace fsd
