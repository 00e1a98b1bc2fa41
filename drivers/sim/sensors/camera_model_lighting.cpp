#include "drivers/sim/sensors/camera_model_lighting.hpp"

#include <algorithm>
#include <cmath>

#include "drivers/sim/world/world_random.hpp"

namespace fsd::sim {

namespace {
constexpr std::uint64_t kGainStream = 0xCA3E6A1u;
constexpr std::uint64_t kBalanceStream = 0xCA3E6A2u;
constexpr std::uint64_t kEventStream = 0xCA3E6A3u;
constexpr double kEventRamp = 0.15;   // fraction of a lighting period spent fading in or out
constexpr double kBrightShare = 0.3;  // of the events, this share are bright spells, the rest shadows
constexpr double kAmbient = 0.6;
constexpr double kDiffuse = 0.55;

double smoothstep(double x) {
  x = std::clamp(x, 0.0, 1.0);
  return x * x * (3.0 - 2.0 * x);
}

// Exposure factor of the shadow or bright spell (if any) of the lighting period that holds t.
double light_event_factor(const CameraConfig& cfg, std::uint64_t seed, Stamp t) {
  if (cfg.light_event_probability <= 0.0 || cfg.light_event_depth <= 0.0) return 1.0;
  const double periods = t / cfg.lighting_period;
  const double slot = std::floor(periods);
  const auto key = static_cast<std::uint64_t>(static_cast<std::int64_t>(slot));
  if (unit_double(hash64(seed, kEventStream, key)) >= cfg.light_event_probability) return 1.0;
  // The event covers the middle of the period with smooth edges.
  const double s = periods - slot;
  const double envelope = smoothstep((s - 0.1) / kEventRamp) * smoothstep((0.9 - s) / kEventRamp);
  const bool bright = unit_double(hash64(seed, kEventStream + 1, key)) < kBrightShare;
  const double change = bright ? 0.5 * cfg.light_event_depth : -cfg.light_event_depth;
  return 1.0 + change * envelope;
}
}  // namespace

cv::Scalar Exposure::channel_gains() const {
  return {gain * (1.0 - white_balance), gain, gain * (1.0 + white_balance)};
}

Exposure exposure_at(const CameraConfig& cfg, std::uint64_t seed, Stamp t) {
  const double phase = t / cfg.lighting_period;
  Exposure e;
  e.gain = cfg.gain * (1.0 + cfg.gain_variation * value_noise(hash64(seed, kGainStream), phase, 0.5, 1.0)) *
           light_event_factor(cfg, seed, t);
  e.gain = std::max(e.gain, 0.05);
  e.white_balance = std::clamp(
      cfg.white_balance + cfg.white_balance_variation * value_noise(hash64(seed, kBalanceStream), phase, 0.5, 1.0),
      -0.9, 0.9);
  return e;
}

Sunlight::Sunlight(const CameraConfig& cfg)
    : to_sun_(std::cos(cfg.sun_elevation) * std::cos(cfg.sun_azimuth),
              std::cos(cfg.sun_elevation) * std::sin(cfg.sun_azimuth), std::sin(cfg.sun_elevation)) {}

double Sunlight::shade(const Vec3& normal) const { return kAmbient + kDiffuse * std::max(0.0, normal.dot(to_sun_)); }

double Sunlight::shade_two_sided(const Vec3& normal) const {
  return kAmbient + kDiffuse * std::abs(normal.dot(to_sun_));
}

cv::Scalar Sunlight::lit(const cv::Vec3d& albedo, double brightness, const cv::Scalar& gains) {
  return {albedo[0] * brightness * gains[0], albedo[1] * brightness * gains[1], albedo[2] * brightness * gains[2]};
}

}  // namespace fsd::sim
