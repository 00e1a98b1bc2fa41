#include "perception/cone_size_filter.hpp"

#include <algorithm>
#include <bitset>
#include <cmath>
#include <limits>

namespace fsd {

const ConfigSection<ConeSizeConfig>& cone_size_section() {
  static const auto s =
      ConfigSection<ConeSizeConfig>("perception.lidar.size")
          .number("small_width", &ConeSizeConfig::small_width, 0.05, 1.0, "m", "Small cone base width (FSG 0.228).")
          .number("small_height", &ConeSizeConfig::small_height, 0.05, 1.5, "m", "Small cone height (FSG 0.325).")
          .number("big_width", &ConeSizeConfig::big_width, 0.05, 1.0, "m", "Big cone base width (FSG 0.285).")
          .number("big_height", &ConeSizeConfig::big_height, 0.05, 1.5, "m", "Big cone height (FSG 0.505).")
          .number("small_top_width", &ConeSizeConfig::small_top_width, 0.0, 0.5, "m", "Small cone tip width.")
          .number("big_top_width", &ConeSizeConfig::big_top_width, 0.0, 0.5, "m", "Big cone tip width.")
          .number("width_margin", &ConeSizeConfig::width_margin, 0.0, 1.0, "m",
                  "A cluster wider than a big cone's base plus this is rejected.")
          .number("height_margin", &ConeSizeConfig::height_margin, 0.0, 1.0, "m",
                  "A cluster taller than a big cone plus this is rejected.")
          .number("profile_margin", &ConeSizeConfig::profile_margin, 0.0, 0.5, "m",
                  "A cluster whose silhouette at some height is wider than a big cone's there by more than this (on "
                  "each side) is not cone-shaped.")
          .number("big_min_height", &ConeSizeConfig::big_min_height, 0.05, 1.5, "m",
                  "A cone whose cluster reaches this high above the ground is a big cone.")
          .number("hit_margin", &ConeSizeConfig::hit_margin, 0.0, 0.5, "m",
                  "Too flat / floating: how far inside a cone the next laser up / down must pass to count as a miss.")
          .number("beam_spacing_deg", &ConeSizeConfig::beam_spacing_deg, 0.1, 10.0, "deg",
                  "Vertical angle between adjacent lasers (VLP-16: 2).")
          .number("lowest_beam_deg", &ConeSizeConfig::lowest_beam_deg, -90.0, 0.0, "deg",
                  "Elevation of the sensor's lowest laser (VLP-16: -15): no laser below it can see a cone's foot.")
          .number("highest_beam_deg", &ConeSizeConfig::highest_beam_deg, 0.0, 90.0, "deg",
                  "Elevation of the sensor's highest laser (VLP-16: 15).")
          .number("azimuth_step_deg", &ConeSizeConfig::azimuth_step_deg, 0.01, 5.0, "deg",
                  "Horizontal angle between firings (VLP-16: 0.2 at 10 Hz).")
          .number("min_point_ratio", &ConeSizeConfig::min_point_ratio, 0.0, 1.0, "",
                  "A cluster with fewer points than this share of a small cone's at that range is rejected.")
          .integer("min_points", &ConeSizeConfig::min_points, 1, 10000, "", "A cone has at least this many points.")
          .number("tall_clearance", &ConeSizeConfig::tall_clearance, 0.0, 5.0, "m",
                  "A cone candidate with obstacle points higher than a big cone this close is part of something "
                  "taller (a fence seen at a grazing angle, a post); 0 = off.");
  return s;
}

const char* to_string(ConeRejection r) {
  switch (r) {
    case ConeRejection::None:
      return "cone";
    case ConeRejection::TooSparse:
      return "too_sparse";
    case ConeRejection::TooWide:
      return "too_wide";
    case ConeRejection::TooTall:
      return "too_tall";
    case ConeRejection::NotConeShaped:
      return "not_cone_shaped";
    case ConeRejection::TooFlat:
      return "too_flat";
    case ConeRejection::Floating:
      return "floating";
    case ConeRejection::BesideTaller:
      return "beside_taller";
    case ConeRejection::Black:
      return "black";
  }
  return "?";
}

double ConeSizeFilter::expected_points(double range, int frames, double low, double high) const {
  const double r = std::max(range, 0.5);
  const double gap = r * std::tan(deg2rad(cfg_.beam_spacing_deg));
  const double visible = std::max(0.0, std::min(high, cfg_.small_height) - low);
  const double rings = std::max(1.0, visible / gap);
  const double mean_width = 0.5 * (cfg_.small_width + cfg_.small_top_width);
  const double across = std::max(1.0, mean_width / (r * deg2rad(cfg_.azimuth_step_deg)));
  return std::max(1, frames) * rings * across;
}

std::vector<Vec2> ConeSizeFilter::tall_points(const std::vector<Point>& cloud, const GroundSurface& ground) const {
  std::vector<Vec2> out;
  if (cfg_.tall_clearance <= 0) return out;
  const double limit = cfg_.big_height + cfg_.height_margin;
  for (const auto& q : cloud)
    if (ground.height_of(q.x, q.y, q.z) > limit) out.emplace_back(q.x, q.y);
  return out;
}

bool ConeSizeFilter::beside_taller(const Vec3& position, const std::vector<Vec2>& tall) const {
  const double r2 = cfg_.tall_clearance * cfg_.tall_clearance;
  const Vec2 p = position.head<2>();
  return std::any_of(tall.begin(), tall.end(), [&](const Vec2& q) { return (q - p).squaredNorm() < r2; });
}

ConeMeasurement ConeSizeFilter::measure(const std::vector<Point>& cloud, const Cluster& cluster,
                                        const GroundSurface& ground, const Pose3& mount, double ground_threshold,
                                        int frames, const LidarShadow* shadow) const {
  const Vec3 sensor = mount.translation();
  ConeMeasurement m;
  ConeCandidate& c = m.candidate;
  const auto n = cluster.indices.size();
  c.points = static_cast<std::uint32_t>(n);
  if (n == 0) {
    m.rejection = ConeRejection::TooSparse;
    return m;
  }
  // Envelope, centroid, heights above the ground.
  Vec3 sum = Vec3::Zero();
  c.min = Vec3::Constant(std::numeric_limits<double>::max());
  c.max = -c.min;
  double top = -std::numeric_limits<double>::max(), bottom = std::numeric_limits<double>::max();
  double intensity = 0;
  std::bitset<256> rings;
  std::vector<double> height(n);
  c.cloud.reserve(n);
  for (std::size_t k = 0; k < n; ++k) {
    const Point& q = cloud[cluster.indices[k]];
    const Vec3 p(q.x, q.y, q.z);
    sum += p;
    c.min = c.min.cwiseMin(p);
    c.max = c.max.cwiseMax(p);
    height[k] = ground.height_of(p.x(), p.y(), p.z());
    top = std::max(top, height[k]);
    bottom = std::min(bottom, height[k]);
    intensity += q.intensity;
    rings.set(q.ring & 0xFF);
    c.cloud.push_back(q);
  }
  c.centroid = sum / static_cast<double>(n);
  c.mean_intensity = static_cast<float>(intensity / static_cast<double>(n));
  c.rings = static_cast<std::uint32_t>(rings.count());
  c.height = top;
  c.bottom = bottom;

  // Line-of-sight axes from the sensor through the centroid, in the ground plane.
  const Vec2 s = sensor.head<2>();
  Vec2 los = c.centroid.head<2>() - s;
  const double range = los.norm();
  los = range > 1e-6 ? Vec2(los / range) : Vec2(1.0, 0.0);
  const Vec2 across(-los.y(), los.x());
  double r0 = std::numeric_limits<double>::max(), r1 = -r0, t0 = r0, t1 = -r0;
  std::vector<double> radial(n), tangential(n);
  for (std::size_t k = 0; k < n; ++k) {
    const Point& q = cloud[cluster.indices[k]];
    const Vec2 d = Vec2(q.x, q.y) - s;
    radial[k] = d.dot(los);
    tangential[k] = d.dot(across);
    r0 = std::min(r0, radial[k]), r1 = std::max(r1, radial[k]);
    t0 = std::min(t0, tangential[k]), t1 = std::max(t1, tangential[k]);
  }
  c.width = std::max(r1 - r0, t1 - t0);

  // Silhouette per height slice (the points one laser left across the cone): its half-width across the line of
  // sight at each height, about the axis in the middle of the whole silhouette.
  const double axis_t = 0.5 * (t0 + t1);
  struct Slice {
    double lo = std::numeric_limits<double>::max(), hi = -std::numeric_limits<double>::max();
    int n = 0;
  };
  constexpr double kSlice = 0.03;  // m: under the 2° laser spacing at 1 m
  const int slices = std::max(1, static_cast<int>(std::ceil((top - bottom) / kSlice)) + 1);
  std::vector<Slice> slice(static_cast<std::size_t>(slices));
  const auto slice_of = [&](double h) { return std::clamp(static_cast<int>((h - bottom) / kSlice), 0, slices - 1); };
  for (std::size_t k = 0; k < n; ++k) {
    Slice& sl = slice[static_cast<std::size_t>(slice_of(height[k]))];
    sl.lo = std::min(sl.lo, tangential[k]), sl.hi = std::max(sl.hi, tangential[k]);
    ++sl.n;
  }
  const auto half_width = [&](const Slice& sl) { return std::max(sl.hi - axis_t, axis_t - sl.lo); };
  const auto radius_at = [](double h, double r_base, double r_top, double height_total) {
    const double f = std::clamp(h / height_total, 0.0, 1.0);
    return r_base - (r_base - r_top) * f;
  };
  const double small_base = 0.5 * cfg_.small_width, small_top = 0.5 * cfg_.small_top_width;
  const double big_base = 0.5 * cfg_.big_width, big_top = 0.5 * cfg_.big_top_width;
  c.big = top >= cfg_.big_min_height;
  // The cone's radius where each point hit it: the small cone's, unless the slice is wider than that by more than
  // half a firing step; then its measured half-width (plus half a step, which it misses on average) up to the big
  // cone's radius there; the big cone's once the cluster is known to be one. A big cone seen only low (one far
  // laser) is thus not placed as a small one.
  const double step = std::max(0.0, range) * deg2rad(cfg_.azimuth_step_deg);
  const auto radius_of_point = [&](std::size_t k) {
    const double h = height[k];
    const double big_r = radius_at(h, big_base, big_top, cfg_.big_height);
    if (c.big) return big_r;
    const double small_r = radius_at(h, small_base, small_top, cfg_.small_height);
    const double half = half_width(slice[static_cast<std::size_t>(slice_of(h))]);
    if (half <= small_r + 0.5 * step) return small_r;  // as wide as a small cone there, within half a firing step
    return std::clamp(half + 0.5 * step, std::min(small_r, big_r), big_r);
  };

  // Position: the silhouette's middle across; along, each point's range plus the cone's depth behind it there.
  double centre_r = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const double rho = radius_of_point(k);
    const double u = std::min(std::abs(tangential[k] - axis_t), rho);
    centre_r += radial[k] + std::sqrt(rho * rho - u * u);
  }
  centre_r /= static_cast<double>(n);
  const Vec2 xy = s + centre_r * los + axis_t * across;
  c.position = Vec3(xy.x(), xy.y(), ground.z_at(xy.x(), xy.y()));
  c.range = (xy - s).norm();

  // The sensor's laser fan towards the cone, as elevations above the ground plane, and the heights its lowest and
  // highest lasers pass there.
  const Vec3 normal = ground.normal();
  const Vec3 in_sensor = mount.inverse() * c.position;
  const double az = -std::atan2(in_sensor.y(), in_sensor.x());
  const auto elevation_of = [&](double laser_deg) {
    const double e = deg2rad(laser_deg);
    const Vec3 d = mount.linear() * Vec3(std::cos(e) * std::cos(az), -std::cos(e) * std::sin(az), std::sin(e));
    return std::asin(std::clamp(d.dot(normal), -1.0, 1.0));
  };
  const double sensor_h = ground.height_of(sensor.x(), sensor.y(), sensor.z());
  const double r = std::max(c.range, 0.1);
  const double lowest = sensor_h + r * std::tan(elevation_of(cfg_.lowest_beam_deg));
  const double highest = sensor_h + r * std::tan(elevation_of(cfg_.highest_beam_deg));
  m.expected_points = expected_points(c.range, frames, std::max(ground_threshold, lowest), highest);
  // A return nearer than the cone's front by more than the range noise hides that azimuth.
  constexpr double kShadowMargin = 0.05;
  if (shadow) m.visible_share = shadow->visible_share(xy, 0.5 * cfg_.small_width, kShadowMargin);

  // The tests, cheapest and most telling first.
  const double gap = c.range * std::tan(deg2rad(cfg_.beam_spacing_deg));
  const double slack = 0.25 * gap;  // a laser a quarter spacing beyond the fan's end is not there
  if (c.width > cfg_.big_width + cfg_.width_margin) {
    m.rejection = ConeRejection::TooWide;
  } else if (top > cfg_.big_height + cfg_.height_margin) {
    m.rejection = ConeRejection::TooTall;
  } else if (static_cast<double>(n) <
             std::max<double>(cfg_.min_points, cfg_.min_point_ratio * m.visible_share * m.expected_points)) {
    m.rejection = ConeRejection::TooSparse;
  } else if (top + gap < cfg_.small_height - cfg_.hit_margin && top + gap <= highest + slack) {
    m.rejection = ConeRejection::TooFlat;
  } else if (bottom - gap > ground_threshold + cfg_.hit_margin && bottom - gap >= lowest - slack) {
    m.rejection = ConeRejection::Floating;
  } else {
    // Silhouette: no slice wider than a big cone at its height (a standing tyre's tread, a box, a post's top).
    for (const auto& sl : slice) {
      if (sl.n < 2) continue;
      const double mid = bottom + (static_cast<double>(&sl - slice.data()) + 0.5) * kSlice;
      if (half_width(sl) > radius_at(mid, big_base, big_top, cfg_.big_height) + cfg_.profile_margin) {
        m.rejection = ConeRejection::NotConeShaped;
        break;
      }
    }
  }
  return m;
}

}  // namespace fsd
