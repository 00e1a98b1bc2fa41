#include "perception/ground_fitter.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <pcl/ModelCoefficients.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/sample_consensus/method_types.h>
#include <pcl/sample_consensus/model_types.h>
#include <pcl/segmentation/sac_segmentation.h>
#include <Eigen/Dense>

namespace fsd {

const ConfigSection<GroundConfig>& ground_section() {
  static const auto s =
      ConfigSection<GroundConfig>("perception.lidar.ground")
          .string("method", &GroundConfig::method, {"grid_lsq", "pcl_sac"},
                  "Ground plane fit: grid_lsq = RANSAC on the lowest point per grid cell, then least squares on the "
                  "inliers; pcl_sac = the paper's PCL SACSegmentation (perpendicular plane) on the whole cloud.")
          .number("distance_threshold", &GroundConfig::distance_threshold, 0.005, 0.5, "m",
                  "Inlier threshold τ: points nearer to the plane are ground and removed.")
          .number("max_tilt_deg", &GroundConfig::max_tilt_deg, 0.5, 30.0, "deg",
                  "The plane's pitch/roll relative to the frame is at most this.")
          .number("height_min", &GroundConfig::height_min, -5.0, 5.0, "m",
                  "Lowest plane height h at the frame origin (vehicle frame: the ground is near 0).")
          .number("height_max", &GroundConfig::height_max, -5.0, 5.0, "m",
                  "Highest plane height h at the frame origin.")
          .integer("iterations", &GroundConfig::iterations, 1, 100000, "", "RANSAC hypotheses per frame.")
          .number("seed_cell", &GroundConfig::seed_cell, 0.1, 10.0, "m",
                  "grid_lsq: grid cell whose lowest point is a RANSAC seed.")
          .integer("min_inliers", &GroundConfig::min_inliers, 3, 1000000, "",
                   "A plane with fewer inlier points is not accepted.")
          .number("grazing_band", &GroundConfig::grazing_band, 0.0, 100.0, "m",
                  "Where the ground band (±τ) is longer than this along a laser, band points well short of their "
                  "laser's neighbours are obstacles (far cones a low sensor hits just above the ground); 0 = off.")
          .number("grazing_drop", &GroundConfig::grazing_drop, 0.001, 0.9, "",
                  "Grazing beams: share of the neighbours' median range a band point must fall short by.")
          .number("grazing_window_deg", &GroundConfig::grazing_window_deg, 0.2, 30.0, "deg",
                  "Grazing beams: azimuth window on each side of a point holding its laser's neighbours.")
          .number("grazing_margin", &GroundConfig::grazing_margin, 0.0, 50.0, "m",
                  "Grazing beams: points this far beyond the region of interest serve as neighbours.")
          .number("fit_radius", &GroundConfig::fit_radius, 2.0, 200.0, "m",
                  "The plane is fitted to the points within this horizontal distance of the frame origin.")
          .number("local_cell", &GroundConfig::local_cell, 0.0, 50.0, "m",
                  "Grid cell of the local ground corrections where the ground bends away from the plane; 0 = off.")
          .number("local_band", &GroundConfig::local_band, 0.01, 1.0, "m",
                  "Local ground: the band around the plane searched for the ground layer (largest correction).")
          .integer("local_min_points", &GroundConfig::local_min_points, 3, 100000, "",
                   "Local ground: points a cell's flat layer needs to correct it.")
          .number("local_min_extent", &GroundConfig::local_min_extent, 0.1, 50.0, "m",
                  "Local ground: horizontal spread a cell's flat layer needs (more than an object's foot).")
          .number("local_min_fill", &GroundConfig::local_min_fill, 0.0, 10.0, "",
                  "Local ground: a cell's flat layer needs at least this share of the returns one laser's ring of "
                  "ground gives over its spread (a row of cones one laser crosses is short runs metres apart); "
                  "0 = no density test.");
  return s;
}

GroundFitter::GroundFitter(const GroundConfig& cfg)
    : cfg_(cfg), max_slope_(std::tan(deg2rad(cfg.max_tilt_deg))), rng_(0x5eed) {}

bool GroundFitter::admissible(double a, double b, double h) const {
  return std::isfinite(a) && std::isfinite(b) && std::isfinite(h) && std::hypot(a, b) <= max_slope_ &&
         h >= cfg_.height_min && h <= cfg_.height_max;
}

GroundPlane GroundFitter::fit(const std::vector<Point>& all) {
  rng_.seed(0x5eed);  // the same cloud gives the same plane, whatever came before
  near_.clear();
  const float r2 = static_cast<float>(cfg_.fit_radius * cfg_.fit_radius);
  for (const auto& q : all)
    if (q.x * q.x + q.y * q.y <= r2) near_.push_back(q);
  const std::vector<Point>& points = near_;
  GroundPlane p = cfg_.method == "pcl_sac" ? fit_pcl_sac(points) : fit_grid_lsq(points);
  if (p.valid && (p.inliers < static_cast<std::size_t>(cfg_.min_inliers) || !admissible(p.a, p.b, p.h)))
    p.valid = false;
  return p;
}

void score_plane(const std::vector<Point>& points, double threshold, GroundPlane& plane) {
  const double k = plane.inv_norm();
  double sq = 0;
  std::size_t m = 0;
  for (const auto& q : points) {
    const double d = (q.z - plane.z_at(q.x, q.y)) * k;
    if (std::abs(d) >= threshold) continue;
    sq += d * d;
    ++m;
  }
  plane.inliers = m;
  plane.rms = m > 0 ? std::sqrt(sq / static_cast<double>(m)) : 0.0;
}

GroundPlane refit_plane(const std::vector<Point>& points, const GroundPlane& plane, double threshold) {
  // Normal equations of z = a·x + b·y + h, centred for conditioning.
  const double k = plane.inv_norm();
  Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
  Eigen::Vector3d rhs = Eigen::Vector3d::Zero();
  std::size_t n = 0;
  for (const auto& q : points) {
    const double d = (q.z - (plane.a * q.x + plane.b * q.y + plane.h)) * k;
    if (std::abs(d) >= threshold) continue;
    const Eigen::Vector3d row(q.x, q.y, 1.0);
    A.noalias() += row * row.transpose();
    rhs.noalias() += row * static_cast<double>(q.z);
    ++n;
  }
  GroundPlane out;
  if (n < 3) return out;
  const Eigen::Vector3d sol = A.ldlt().solve(rhs);
  if (!sol.allFinite()) return out;
  out.a = sol.x();
  out.b = sol.y();
  out.h = sol.z();
  out.valid = true;
  score_plane(points, threshold, out);
  return out;
}

GroundPlane GroundFitter::fit_grid_lsq(const std::vector<Point>& points) {
  GroundPlane none;
  if (points.size() < 3) return none;
  // Seeds: the lowest point of each occupied cell, among points that could be on an admissible plane (a point far
  // below the lowest plane the bounds allow is noise or a reflection).
  float x0 = std::numeric_limits<float>::max(), y0 = x0, x1 = -x0, y1 = -x0;
  for (const auto& q : points) {
    x0 = std::min(x0, q.x), x1 = std::max(x1, q.x);
    y0 = std::min(y0, q.y), y1 = std::max(y1, q.y);
  }
  double cell = cfg_.seed_cell;
  // At most ~65 k cells whatever the extent of the cloud.
  while ((x1 - x0) / cell * (y1 - y0) / cell > 65536.0) cell *= 2;
  const int nx = static_cast<int>((x1 - x0) / cell) + 1, ny = static_cast<int>((y1 - y0) / cell) + 1;
  cell_lowest_.assign(static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny), -1);
  const float inv = static_cast<float>(1.0 / cell);
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto& q = points[i];
    const double r = std::hypot(q.x, q.y);
    if (q.z < cfg_.height_min - max_slope_ * r - cfg_.distance_threshold) continue;
    const int cx = std::min(nx - 1, static_cast<int>((q.x - x0) * inv));
    const int cy = std::min(ny - 1, static_cast<int>((q.y - y0) * inv));
    int& slot =
        cell_lowest_[static_cast<std::size_t>(cy) * static_cast<std::size_t>(nx) + static_cast<std::size_t>(cx)];
    if (slot < 0 || q.z < points[static_cast<std::size_t>(slot)].z) slot = static_cast<int>(i);
  }
  seeds_.clear();
  for (int idx : cell_lowest_)
    if (idx >= 0) {
      const auto& q = points[static_cast<std::size_t>(idx)];
      seeds_.emplace_back(q.x, q.y, q.z);
    }
  if (seeds_.size() < 3) return none;

  // RANSAC over the seeds: the admissible plane through three seeds with the most seeds within τ.
  const auto n = static_cast<std::uint32_t>(seeds_.size());
  const double tau = cfg_.distance_threshold;
  std::size_t best_count = 0;
  double best_sq = 0;
  GroundPlane best;
  for (int it = 0; it < cfg_.iterations; ++it) {
    const auto& p0 = seeds_[rng_() % n];
    const auto& p1 = seeds_[rng_() % n];
    const auto& p2 = seeds_[rng_() % n];
    const Eigen::Vector3d u = (p1 - p0).cast<double>(), v = (p2 - p0).cast<double>();
    const Eigen::Vector3d nrm = u.cross(v);
    if (std::abs(nrm.z()) < 1e-9 || nrm.norm() < 1e-6) continue;  // degenerate or vertical
    const double a = -nrm.x() / nrm.z(), b = -nrm.y() / nrm.z();
    const double h = p0.z() - a * p0.x() - b * p0.y();
    if (!admissible(a, b, h)) continue;
    const double k = 1.0 / std::sqrt(1.0 + a * a + b * b);
    std::size_t count = 0;
    double sq = 0;
    for (const auto& s : seeds_) {
      const double d = (s.z() - (a * s.x() + b * s.y() + h)) * k;
      if (std::abs(d) < tau) ++count, sq += d * d;
    }
    if (count > best_count || (count == best_count && sq < best_sq)) {
      best_count = count;
      best_sq = sq;
      best.a = a, best.b = b, best.h = h, best.valid = true;
    }
  }
  if (!best.valid) return none;
  // Least squares on every point near the hypothesis, then once more on the points near the refined plane.
  for (int pass = 0; pass < 2; ++pass) {
    const GroundPlane refined = refit_plane(points, best, tau);
    if (!refined.valid || !admissible(refined.a, refined.b, refined.h)) break;
    best = refined;
  }
  if (best.inliers == 0) score_plane(points, tau, best);  // no refit succeeded: the RANSAC plane as it is
  return best;
}

GroundPlane GroundFitter::fit_pcl_sac(const std::vector<Point>& points) const {
  GroundPlane out;
  if (points.size() < 3) return out;
  pcl::PointCloud<pcl::PointXYZ>::Ptr cloud(new pcl::PointCloud<pcl::PointXYZ>);
  cloud->points.reserve(points.size());
  for (const auto& q : points) cloud->points.emplace_back(q.x, q.y, q.z);
  cloud->width = static_cast<std::uint32_t>(cloud->points.size());
  cloud->height = 1;
  pcl::SACSegmentation<pcl::PointXYZ> seg;
  seg.setOptimizeCoefficients(true);
  seg.setModelType(pcl::SACMODEL_PERPENDICULAR_PLANE);
  seg.setMethodType(pcl::SAC_RANSAC);
  seg.setAxis(Eigen::Vector3f::UnitZ());
  seg.setEpsAngle(deg2rad(cfg_.max_tilt_deg));
  seg.setDistanceThreshold(cfg_.distance_threshold);
  seg.setMaxIterations(cfg_.iterations);
  seg.setInputCloud(cloud);
  pcl::PointIndices inliers;
  pcl::ModelCoefficients coeff;
  seg.segment(inliers, coeff);
  if (coeff.values.size() != 4 || inliers.indices.empty()) return out;
  const double nx = coeff.values[0], ny = coeff.values[1], nz = coeff.values[2], d = coeff.values[3];
  if (std::abs(nz) < 1e-6) return out;
  out.a = -nx / nz;
  out.b = -ny / nz;
  out.h = -d / nz;
  out.valid = true;
  double sq = 0;
  for (int i : inliers.indices) {
    const auto& q = points[static_cast<std::size_t>(i)];
    const double e = out.height_of(q.x, q.y, q.z);
    sq += e * e;
  }
  out.inliers = inliers.indices.size();
  out.rms = std::sqrt(sq / static_cast<double>(out.inliers));
  return out;
}

}  // namespace fsd
