#include "drivers/sim/sensors/lidar_model.hpp"

#include <algorithm>
#include <cmath>

#include "common/rotation.hpp"
#include "drivers/sim/world/world_random.hpp"

namespace fsd::sim {

namespace vlp = wire::vlp16;

namespace {
// Standard normal truncated at ±2, drawn by inverse CDF from a table of its 2048 quantiles (steps of < 0.02σ,
// well below the 2 mm range unit), so a draw costs one table look-up instead of a log and a cosine.
double truncated_normal(std::uint64_t h) {
  constexpr int kLevels = 2048;
  static const std::array<double, kLevels> quantiles = [] {
    std::array<double, kLevels> q{};
    auto cdf = [](double x) { return 0.5 * std::erfc(-x / std::numbers::sqrt2); };
    const double lo = cdf(-2.0), hi = cdf(2.0);
    for (int i = 0; i < kLevels; ++i) {
      const double p = lo + (hi - lo) * (i + 0.5) / kLevels;
      double a = -2.0, b = 2.0;
      for (int it = 0; it < 50; ++it) ((cdf(0.5 * (a + b)) < p) ? a : b) = 0.5 * (a + b);
      q[static_cast<std::size_t>(i)] = 0.5 * (a + b);
    }
    return q;
  }();
  return quantiles[h >> 53];  // top 11 bits
}
}  // namespace

const ConfigSection<LidarConfig>& lidar_section() {
  using C = LidarConfig;
  static const auto s =
      ConfigSection<C>("sim.lidar")
          .number("rotation_hz", &C::rotation_hz, 5.0, 20.0, "Hz", "Rotation rate (VLP-16: 300..1200 rpm).")
          .number(
              "range_noise", &C::range_noise, 0.0, 0.5, "m",
              "Range accuracy as a 2-sigma bound: normal noise with sigma = range_noise/2, truncated at ±range_noise.")
          .number("dropout", &C::dropout, 0.0, 1.0, "", "Probability that a return is lost.")
          .number("max_range", &C::max_range, 1.0, 130.0, "m", "Farthest return (the wire format holds 131 m).")
          .number("min_range", &C::min_range, 0.0, 5.0, "m", "Nearest return.")
          .number("latency", &C::latency, 0.0, 0.1, "s", "From a packet's last firing to its departure.")
          .number("beam_aperture", &C::beam_aperture, 0.0, 0.05, "m",
                  "Vertical size of a beam at the sensor: a cone's paints are averaged over the footprint.")
          .number("beam_divergence", &C::beam_divergence, 0.0, 0.01, "rad",
                  "Vertical divergence of a beam (full angle): the footprint grows by this per metre.")
          .string("return_mode", &C::return_mode, {"strongest", "last"}, "Return mode reported in the factory bytes.")
          .integer("product_id", &C::product_id, 0, 255, "",
                   "Product id in the factory bytes: 34 (0x22) VLP-16, 33 (0x21) early firmware.");
  return s;
}

Pose3 lidar_mount(const LidarConfig& cfg) { return pose_zyx(Vec3(cfg.x, cfg.y, cfg.z), cfg.yaw, cfg.pitch, cfg.roll); }

LidarModel::LidarModel(const LidarConfig& cfg, const World& world, std::uint64_t seed, Stamp start)
    : cfg_(cfg),
      world_(world),
      seed_(seed),
      start_(start),
      mount_(lidar_mount(cfg)),
      return_mode_(cfg.return_mode == "last" ? vlp::kReturnLast : vlp::kReturnStrongest) {
  for (std::size_t k = 0; k < vlp::kLasers; ++k) {
    cos_elev_[k] = std::cos(deg2rad(vlp::kLaserTable[k].elevation_deg));
    sin_elev_[k] = std::sin(deg2rad(vlp::kLaserTable[k].elevation_deg));
    offset_[k] = vlp::kLaserTable[k].vertical_offset_m;
  }
  const double step = 2.0 * std::numbers::pi * cfg.rotation_hz * vlp::kFiringPeriodUs * 1e-6;
  cos_step_ = std::cos(step);
  sin_step_ = std::sin(step);
}

Stamp LidarModel::next_packet_start() const {
  return start_ + static_cast<double>(packets_) * vlp::kPacketPeriodUs * 1e-6;
}

double LidarModel::azimuth_rad(Stamp t) const {
  const double turns = cfg_.rotation_hz * (t - start_);
  return 2.0 * std::numbers::pi * (turns - std::floor(turns));
}

void LidarModel::advance_to(Stamp t, const std::function<Pose3(Stamp)>& body_pose_at, const ByteSink& sink) {
  constexpr double kPacket = vlp::kPacketPeriodUs * 1e-6;
  while (next_packet_start() + kPacket <= t) {
    const Stamp departure = next_packet_start() + kPacket + cfg_.latency;
    build_packet(body_pose_at);
    ++packets_;
    if (sink) sink(departure, packet_);
  }
}

void LidarModel::build_packet(const std::function<Pose3(Stamp)>& body_pose_at) {
  const Stamp t0 = next_packet_start();
  const double noise_sigma = cfg_.range_noise / 2.0;
  for (std::size_t block = 0; block < vlp::kBlocks; ++block) {
    const std::size_t at = block * vlp::kBlockSize;
    const Stamp t_block = t0 + static_cast<double>(block) * vlp::kBlockPeriodUs * 1e-6;
    packet_[at] = vlp::kFlag0;
    packet_[at + 1] = vlp::kFlag1;
    const auto az =
        static_cast<std::uint16_t>(std::lround(rad2deg(azimuth_rad(t_block)) / vlp::kAzimuthUnitDeg) % 36000);
    vlp::write_u16(packet_, at + 2, az);
    for (std::size_t seq = 0; seq < vlp::kSequencesPerBlock; ++seq) {
      const Stamp t_seq = t_block + static_cast<double>(seq) * vlp::kSequencePeriodUs * 1e-6;
      const Pose3 sensor = body_pose_at(t_seq) * mount_;  // map ← sensor during this sequence
      const Eigen::Matrix3d R = sensor.linear();
      // Azimuth of each laser's firing: the head turns by a fixed angle between lasers, applied as a rotation.
      const double alpha0 = azimuth_rad(t_seq);
      double cos_a = std::cos(alpha0), sin_a = std::sin(alpha0);
      for (std::size_t k = 0; k < vlp::kLasers; ++k) {
        const std::size_t ch = vlp::channel_offset(block, seq, k);
        if (k > 0) {
          const double c = cos_a * cos_step_ - sin_a * sin_step_;
          sin_a = sin_a * cos_step_ + cos_a * sin_step_;
          cos_a = c;
        }
        const Vec3 dir_s(cos_elev_[k] * cos_a, -cos_elev_[k] * sin_a, sin_elev_[k]);
        const Vec3 dir = R * dir_s;
        const Vec3 origin = sensor * Vec3(0.0, 0.0, offset_[k]);
        const auto hit = world_.raycast(origin, dir, cfg_.max_range + cfg_.range_noise,
                                        Beam{cfg_.beam_aperture, cfg_.beam_divergence});

        std::uint16_t counts = 0;
        std::uint8_t intensity = 0;
        if (hit) {
          const std::uint64_t h = hash64(seed_, packets_, (block * vlp::kSequencesPerBlock + seq) * vlp::kLasers + k);
          const bool dropped = cfg_.dropout > 0.0 && unit_double(mix64(h ^ 0xD50Fu)) < cfg_.dropout;
          const double noise = noise_sigma * truncated_normal(mix64(h ^ 0x7015Eu));
          const double d = hit->distance + noise;
          if (!dropped && d >= cfg_.min_range && d <= cfg_.max_range) {
            counts = static_cast<std::uint16_t>(std::clamp(std::lround(d / vlp::kDistanceUnit), 1L, 65535L));
            const double incidence = std::abs(hit->normal.dot(dir));
            intensity = static_cast<std::uint8_t>(
                std::clamp(std::lround(hit->reflectivity * (0.3 + 0.7 * incidence)), 0L, 255L));
            if (hit->cone >= 0) count_cone_return(hit->cone, t_seq);
          }
        }
        vlp::write_u16(packet_, ch, counts);
        packet_[ch + 2] = intensity;
      }
    }
  }
  // µs past the top of the hour of the packet's first firing.
  const double past_hour = t0 - 3600.0 * std::floor(t0 / 3600.0);
  vlp::write_u32(packet_, vlp::kTimestampOffset,
                 static_cast<std::uint32_t>(std::llround(past_hour * 1e6) % 3600000000LL));
  packet_[vlp::kReturnModeOffset] = return_mode_;
  packet_[vlp::kProductOffset] = static_cast<std::uint8_t>(cfg_.product_id);
}

void LidarModel::count_cone_return(int cone, Stamp t) {
  // A few cones per packet, and the same cone over consecutive firings: the last entry first.
  auto it =
      std::find_if(cone_returns_.rbegin(), cone_returns_.rend(), [cone](const auto& c) { return c.cone == cone; });
  if (it == cone_returns_.rend()) {
    cone_returns_.push_back({cone, 1, t});
    return;
  }
  ++it->returns;
  it->t = t;
}

}  // namespace fsd::sim
