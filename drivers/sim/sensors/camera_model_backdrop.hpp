#pragma once
// Sky and ground of the virtual camera. The ground is a plane, so its image is a homography of a top-down texture:
// one cv::warpPerspective per frame paints asphalt and grass (World::ground_surface, with seeded brightness noise
// at several scales) without casting a ray per pixel. Above the ground's vanishing line the sky is a gradient with
// faint clouds.
#include <cstdint>

#include <opencv2/core/mat.hpp>

#include "drivers/sim/sensors/camera_model_view.hpp"
#include "drivers/sim/world/world.hpp"

namespace fsd::sim {

class Backdrop {
 public:
  Backdrop(const World& world, const CameraConfig& cfg, std::uint64_t seed);

  // Paints every pixel of `frame` (CV_8UC3, the view's size) with sky or ground under the exposure gains.
  void paint(const CameraView& view, const cv::Scalar& gains, cv::Mat& frame) const;

 private:
  const World& world_;
  cv::Mat texture_;  // CV_8UC3; texel (column j, row i) shows the map point (x0 + j·res, y0 + i·res)
  double x0_ = 0, y0_ = 0, res_ = 0.1;
  cv::Scalar beyond_;  // colour of the ground outside the texture
  cv::Mat sky_;        // CV_8UC3 gradient, the image's size
};

}  // namespace fsd::sim
