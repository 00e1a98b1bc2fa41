#pragma once
// Scene lighting of the virtual camera: the sun for shading surfaces, and the exposure seen through the camera
// (gain and white balance) as a deterministic function of time and seed, so that a frame's look does not depend
// on how the simulation is stepped.
#include <cstdint>

#include <opencv2/core/types.hpp>

#include "common/geometry.hpp"
#include "common/time.hpp"
#include "drivers/sim/sensors/camera_model_config.hpp"

namespace fsd::sim {

struct Exposure {
  double gain = 1.0;           // multiplies every channel
  double white_balance = 0.0;  // red × (1 + w), blue × (1 − w)

  // Per-channel factors in OpenCV's B, G, R order.
  cv::Scalar channel_gains() const;
};

// Exposure at capture time t: smooth drift plus occasional shadows (darker) and bright spells.
Exposure exposure_at(const CameraConfig& cfg, std::uint64_t seed, Stamp t);

class Sunlight {
 public:
  explicit Sunlight(const CameraConfig& cfg);
  const Vec3& direction() const { return to_sun_; }  // unit vector towards the sun, map frame
  // Brightness factor of a surface with this outward normal (map frame): ambient sky light plus Lambert sun.
  double shade(const Vec3& normal) const;
  // The same for a thin two-sided surface (fence).
  double shade_two_sided(const Vec3& normal) const;
  // Colour of an albedo (B, G, R, 0..255) under this brightness and the exposure.
  static cv::Scalar lit(const cv::Vec3d& albedo, double brightness, const cv::Scalar& channel_gains);

 private:
  Vec3 to_sun_;
};

}  // namespace fsd::sim
