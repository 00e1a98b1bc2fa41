#include "perception/touching_cones.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>

namespace fsd {

const ConfigSection<TouchingConesConfig>& touching_cones_section() {
  static const auto s =
      ConfigSection<TouchingConesConfig>("perception.lidar.touching")
          .boolean("enabled", &TouchingConesConfig::enabled,
                   "Split a cluster too wide for one cone into the cones touching in it, by their separate tips.")
          .number("tip_height", &TouchingConesConfig::tip_height, 0.02, 0.5, "m",
                  "Points higher than this above the ground are a cone's upper part.")
          .number("tip_tolerance", &TouchingConesConfig::tip_tolerance, 0.01, 0.5, "m",
                  "Upper points nearer than this (or 1.5 azimuth steps at their range) are one cone's.")
          .number("min_height_span", &TouchingConesConfig::min_height_span, 0.0, 0.5, "m",
                  "A part whose returns span less height than this (one laser) needs returns brighter than black "
                  "rubber to count (perception.lidar.colour.black_max; calibrated reflectivity only).")
          .number("min_separation", &TouchingConesConfig::min_separation, 0.05, 1.0, "m",
                  "Two upper parts nearer than this are not two cones: the cluster is not split.")
          .number("reach", &TouchingConesConfig::reach, 0.05, 1.0, "m",
                  "A point belongs to the nearest upper part's axis within this distance.")
          .number("max_width", &TouchingConesConfig::max_width, 0.1, 10.0, "m",
                  "Clusters wider than this (diagonal of the footprint) are not split.")
          .number("min_explained", &TouchingConesConfig::min_explained, 0.5, 1.0, "",
                  "Share of the cluster's points the parts must hold, else it is not split.")
          .integer("min_tip_points", &TouchingConesConfig::min_tip_points, 1, 1000, "", "Upper points a part needs.");
  return s;
}

namespace {

ClusterConfig tip_clustering(const TouchingConesConfig& cfg, double azimuth_step_deg) {
  ClusterConfig c;
  c.tolerance = cfg.tip_tolerance;
  c.range_factor = 1.5 * deg2rad(azimuth_step_deg);  // neighbouring firings along one laser's arc stay together
  c.min_points = std::max(1, cfg.min_tip_points);
  return c;
}

}  // namespace

// Between two cones' tips side by side a laser passes through air for a firing or more, and from one tip to a tip
// behind it the range jumps; upper points that are consecutive firings of one laser (same revolution) within a
// cone's base radius of each other are one continuous top, however far apart for the tolerance (a kerb's arc far
// away, its returns spaced wider along it than across the line of sight): their groups are one.
std::vector<Cluster> TouchingConesSplitter::join_continuous(std::vector<Cluster> groups) const {
  if (groups.size() < 2) return groups;
  constexpr double kSameRevolution = 0.01;  // s: consecutive firings are microseconds apart, revolutions 0.1 s
  std::vector<std::size_t> group_of(high_.size(), 0), parent(groups.size());
  for (std::size_t g = 0; g < groups.size(); ++g) {
    parent[g] = g;
    for (const auto k : groups[g].indices) group_of[k] = g;
  }
  const auto root = [&](std::size_t g) {
    while (parent[g] != g) g = parent[g] = parent[parent[g]];
    return g;
  };
  for (std::size_t i = 0; i < high_.size(); ++i)
    for (std::size_t j = i + 1; j < high_.size(); ++j) {
      const Point &a = high_[i], &b = high_[j];
      if (a.ring != b.ring || std::abs(a.t - b.t) > kSameRevolution) continue;
      const double d_az = std::abs(wrap_angle(static_cast<double>(a.azimuth) - b.azimuth));
      const double d_xy = std::hypot(a.x - b.x, a.y - b.y);
      if (d_az > 0 && d_az <= 1.5 * azimuth_step_ && d_xy <= cfg_.reach) parent[root(group_of[i])] = root(group_of[j]);
    }
  std::vector<Cluster> joined;
  std::vector<std::ptrdiff_t> slot(groups.size(), -1);
  for (std::size_t g = 0; g < groups.size(); ++g) {
    const std::size_t r = root(g);
    if (slot[r] < 0) {
      slot[r] = static_cast<std::ptrdiff_t>(joined.size());
      joined.emplace_back();
    }
    auto& into = joined[static_cast<std::size_t>(slot[r])].indices;
    into.insert(into.end(), groups[g].indices.begin(), groups[g].indices.end());
  }
  return joined;
}

TouchingConesSplitter::TouchingConesSplitter(const TouchingConesConfig& cfg, double azimuth_step_deg, double dark_max)
    : cfg_(cfg),
      dark_max_(dark_max),
      azimuth_step_(deg2rad(azimuth_step_deg)),
      tips_(tip_clustering(cfg, azimuth_step_deg)) {}

std::vector<Cluster> TouchingConesSplitter::split(const std::vector<Point>& cloud, const Cluster& cluster,
                                                  const GroundSurface& ground, const Vec2& sensor_xy) {
  if (!cfg_.enabled || cluster.indices.size() < 2) return {};
  float x0 = std::numeric_limits<float>::max(), y0 = x0, x1 = -x0, y1 = -x0;
  high_.clear();
  for (const auto i : cluster.indices) {
    const Point& q = cloud[i];
    x0 = std::min(x0, q.x), x1 = std::max(x1, q.x), y0 = std::min(y0, q.y), y1 = std::max(y1, q.y);
    if (ground.height_of(q.x, q.y, q.z) > cfg_.tip_height) high_.push_back(q);
  }
  if (std::hypot(x1 - x0, y1 - y0) > cfg_.max_width) return {};
  const auto groups = join_continuous(tips_.cluster(high_, sensor_xy));
  if (groups.size() < 2) return {};
  std::vector<Vec2> axis;
  for (const auto& g : groups) {
    Vec2 sum = Vec2::Zero();
    for (const auto k : g.indices) sum += Vec2(high_[k].x, high_[k].y);
    axis.push_back(sum / static_cast<double>(g.indices.size()));
  }
  for (std::size_t a = 0; a < axis.size(); ++a)
    for (std::size_t b = a + 1; b < axis.size(); ++b)
      if ((axis[a] - axis[b]).norm() < cfg_.min_separation) return {};

  std::vector<Cluster> parts(axis.size());
  std::size_t explained = 0;
  const double reach2 = cfg_.reach * cfg_.reach;
  for (const auto i : cluster.indices) {
    const Vec2 p(cloud[i].x, cloud[i].y);
    std::size_t best = 0;
    double best_d2 = std::numeric_limits<double>::max();
    for (std::size_t a = 0; a < axis.size(); ++a) {
      const double d2 = (p - axis[a]).squaredNorm();
      if (d2 < best_d2) best_d2 = d2, best = a;
    }
    if (best_d2 > reach2) continue;
    parts[best].indices.push_back(i);
    ++explained;
  }
  if (static_cast<double>(explained) < cfg_.min_explained * static_cast<double>(cluster.indices.size())) return {};
  // Evidence that each part is a cone and not a piece of something dark: its narrowing over two heights, or paint.
  for (const auto& part : parts) {
    double lo = std::numeric_limits<double>::max(), hi = -lo;
    float brightest = 0;
    for (const auto i : part.indices) {
      const double h = ground.height_of(cloud[i].x, cloud[i].y, cloud[i].z);
      lo = std::min(lo, h), hi = std::max(hi, h);
      brightest = std::max(brightest, cloud[i].intensity);
    }
    const bool shape = hi - lo >= cfg_.min_height_span;
    const bool paint = dark_max_ >= 0 && brightest > dark_max_;
    if (!shape && !paint) return {};
  }
  return parts;
}

}  // namespace fsd
