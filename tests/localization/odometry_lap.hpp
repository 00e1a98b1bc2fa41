#pragma once
// One lap of scans rendered by the virtual car's VLP-16 (sim_lidar_drive.hpp), the LiDAR odometry integrated from
// the true start pose, and its error against the simulator's true poses. Shared by the lap test
// (lidar_odometry_test.cpp) and the bench (bench/lidar_odometry_bench.cpp).
#include <time.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "common/thread_cpu.hpp"
#include "localization/lidar_odometry/lidar_odometry.hpp"
#include "tests/perception/sim_lidar_drive.hpp"

namespace fsd::test {

struct OdometryLapResult {
  double distance = 0;   // m, true path length
  double end_error = 0;  // m, planar distance between the odometry's and the true pose at the end
  double drift_pct = 0;  // end_error / distance
  double kitti_pct = 0;  // mean relative planar translation error over 50 m segments, per distance
  double yaw_error_deg = 0;
  double max_scan_yaw_error_deg = 0;  // worst per-scan increment yaw error
  int degenerate = 0, scans = 0;
  std::vector<double> cpu_ms;  // CPU time of process() per scan (thread CPU clock: one core, load-independent)
  double p50_ms() const { return percentile(0.5); }
  double p99_ms() const { return percentile(0.99); }
  double percentile(double q) const {
    if (cpu_ms.empty()) return 0;
    std::vector<double> v = cpu_ms;
    const auto k = std::size_t(std::min<double>(double(v.size() - 1), std::floor(q * double(v.size()))));
    std::nth_element(v.begin(), v.begin() + long(k), v.end());
    return v[k];
  }
};

inline double thread_cpu_ms() { return 1e3 * thread_cpu_seconds(); }

// Drives one lap of `track` at `speed` and integrates the odometry from the true starting pose. `trace`: one line per
// scan on stdout (true and estimated increment, their difference, the diagnostics). The car already drives at the
// first scan; `known_start_speed` hands the odometry that speed (else it starts from a standing prediction).
// `measured_motion`: each scan comes with the car's true mean body twist over it (forward speed and yaw rate), as
// the daemon hands it the wheel speed and the GNSS-INS yaw rate.
inline OdometryLapResult drive_odometry_lap(const std::string& track, double speed,
                                            const lidar_odometry::LidarOdometryConfig& cfg = {}, bool trace = false,
                                            bool known_start_speed = false, bool measured_motion = false) {
  SimLidarSetup setup;
  setup.track = track;
  setup.speed = speed;
  SimLidarDrive drive(setup);
  lidar_odometry::LidarOdometry odo(cfg, drive.mount());
  const double lap = drive.drive().length();
  OdometryLapResult r;
  std::vector<std::pair<Pose3, Pose3>> poses;  // (truth, odometry)
  for (;;) {
    const Scan scan = drive.next();
    const Stamp t = firing_span(scan).last;
    if (!odo.started()) {
      lidar_odometry::Vec6 twist = lidar_odometry::Vec6::Zero();
      if (known_start_speed) twist[0] = speed;  // the wheel speed a car would know at a flying start
      odo.start_at(drive.body_pose(t), twist);
    }
    std::optional<lidar_odometry::Vec6> twist;
    if (measured_motion) {
      const FiringSpan span = firing_span(scan);
      const double dt = std::max(span.last - span.first, 1e-3);
      const Pose2 d = to_pose2(drive.body_pose(span.first).inverse() * drive.body_pose(span.last));
      twist = lidar_odometry::Vec6::Zero();
      (*twist)[0] = std::hypot(d.x, d.y) / dt;
      (*twist)[5] = d.yaw / dt;
    }
    const double c0 = thread_cpu_ms();
    const auto out = odo.process(scan, twist);
    r.cpu_ms.push_back(thread_cpu_ms() - c0);
    r.degenerate += out.diagnostics.degenerate;
    ++r.scans;
    poses.emplace_back(drive.body_pose(t), out.pose);
    if (poses.size() >= 2) {
      const auto& a = poses[poses.size() - 2];
      const auto& b = poses.back();
      const Pose2 dt = to_pose2(a.first.inverse() * b.first), de = to_pose2(a.second.inverse() * b.second);
      const double eyaw = rad2deg(wrap_angle(de.yaw - dt.yaw));
      r.max_scan_yaw_error_deg = std::max(r.max_scan_yaw_error_deg, std::abs(eyaw));
      if (trace) {
        const auto& d = out.diagnostics;
        std::printf(
            "%4d true %7.4f %7.4f %7.3f est %7.4f %7.4f %7.3f err %7.4f %7.4f %7.3f deg | e %3d/%3d p %4d/%4d it %2d "
            "minI %8.2f deg %d rms %.3f\n",
            r.scans, dt.x, dt.y, rad2deg(dt.yaw), de.x, de.y, rad2deg(de.yaw), de.x - dt.x, de.y - dt.y, eyaw,
            d.edge_matches, d.edges, d.plane_matches, d.planes, d.iterations, d.min_information,
            d.degenerate_directions, d.rms);
      }
    }
    if (speed * t >= lap) break;
  }
  for (std::size_t i = 1; i < poses.size(); ++i)
    r.distance += (poses[i].first.translation() - poses[i - 1].first.translation()).norm();
  r.end_error = (poses.back().first.translation() - poses.back().second.translation()).head<2>().norm();
  r.drift_pct = 100 * r.end_error / r.distance;
  r.yaw_error_deg = rad2deg(wrap_angle(to_pose2(poses.back().second).yaw - to_pose2(poses.back().first).yaw));
  double sum = 0;
  int n = 0;
  const double seg = 50;
  for (std::size_t i = 0; i < poses.size(); i += 5) {
    double d = 0;
    std::size_t j = i + 1;
    for (; j < poses.size() && d < seg; ++j)
      d += (poses[j].first.translation() - poses[j - 1].first.translation()).norm();
    if (d < seg) break;
    --j;
    const Pose3 dt = poses[i].first.inverse() * poses[j].first, de = poses[i].second.inverse() * poses[j].second;
    sum += (dt.inverse() * de).translation().head<2>().norm() / d;
    ++n;
  }
  r.kitti_pct = n ? 100 * sum / n : 0;
  return r;
}

}  // namespace fsd::test
