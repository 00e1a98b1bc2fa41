#include "daemon/scoring/odometry_score.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <nlohmann/json.hpp>

namespace fsd {

namespace {
double r4(double v) { return std::round(v * 1e4) / 1e4; }
double dist(const Pose2& a, const Pose2& b) { return (a.position() - b.position()).norm(); }
}  // namespace

Drift drift_of(const std::vector<PosePair>& track, double segment) {
  Drift d;
  if (track.size() < 2) return d;
  std::vector<double> along(track.size(), 0.0);  // true distance driven to each pair
  for (std::size_t i = 1; i < track.size(); ++i) along[i] = along[i - 1] + dist(track[i].truth, track[i - 1].truth);
  d.distance_m = along.back();
  d.end_error_m = dist(track.back().truth, track.back().estimate);
  d.end_pct = d.distance_m > 0 ? 100 * d.end_error_m / d.distance_m : 0;
  // Every segment starting at a pair, ending at the first pair `segment` metres further on: the estimate's
  // relative motion against the truth's, seen from the segment's start.
  double sum = 0;
  std::size_t j = 0;
  for (std::size_t i = 0; i < track.size(); ++i) {
    j = std::max(j, i);
    while (j < track.size() && along[j] - along[i] < segment) ++j;
    if (j == track.size()) break;
    const Pose2 dt = track[i].truth.inverse() * track[j].truth;
    const Pose2 de = track[i].estimate.inverse() * track[j].estimate;
    sum += (dt.position() - de.position()).norm() / (along[j] - along[i]);
    ++d.segments;
  }
  d.segment_pct = d.segments ? 100 * sum / d.segments : 0;
  return d;
}

void OdometryScore::keep(std::vector<PosePair>& track, const PosePair& p, double spacing) {
  // The first pair, then one each `spacing` metres; the newest always replaces a closer tail, so the end is exact.
  if (track.size() >= 2 && dist(track[track.size() - 2].truth, track.back().truth) < spacing)
    track.back() = p;
  else
    track.push_back(p);
}

void OdometryScore::add_state(const Pose2& truth, const Pose2& estimate) {
  const double e = dist(truth, estimate);
  sum_sq_ += e * e;
  max_ = std::max(max_, e);
  const double yaw = std::abs(wrap_angle(estimate.yaw - truth.yaw));
  yaw_sum_sq_ += yaw * yaw;
  yaw_max_ = std::max(yaw_max_, yaw);
  ++samples_;
}

void OdometryScore::add_lidar(const Pose2& truth, const Pose2& estimate) {
  keep(lidar_, {truth, estimate}, spacing_);
  ++scans_;
}

nlohmann::json OdometryScore::to_json(const std::string& source) const {
  nlohmann::json j = {
      {"source", source},
      {"ate_m", r4(samples_ ? std::sqrt(sum_sq_ / double(samples_)) : 0.0)},
      {"ate_max_m", r4(max_)},
      {"yaw_rms_deg", r4(samples_ ? std::sqrt(yaw_sum_sq_ / double(samples_)) * 180 / std::numbers::pi : 0.0)},
      {"yaw_max_deg", r4(yaw_max_ * 180 / std::numbers::pi)},
      {"samples", samples_}};
  if (scans_ > 0) {
    const Drift d = drift_of(lidar_);
    j["drift_pct"] = r4(d.end_pct);
    j["lidar"] = {{"distance_m", r4(d.distance_m)}, {"end_error_m", r4(d.end_error_m)},
                  {"drift_pct", r4(d.end_pct)},     {"segment_drift_pct", r4(d.segment_pct)},
                  {"segments", d.segments},         {"scans", scans_}};
  }
  return j;
}

}  // namespace fsd
