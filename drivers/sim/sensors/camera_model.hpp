#pragma once
// The virtual car's camera: renders the World through a pinhole at a fixed rate and emits each frame as a JPEG
// image, what an MJPEG camera sends, to a ByteSink stamped with the capture time plus latency.
//
// Rendering is rasterisation with OpenCV, not ray casting, so it runs many times faster than real time: the sky
// and the ground (one perspective warp of a top-down texture, see camera_model_backdrop.hpp), the objects' ground
// shadows, then cones (with their stripes; fallen cones on their side), tyres, tyre stacks, posts and fence
// panels as shaded polygons, far to near (camera_model_scene.hpp). The exposure (gain and white balance) drifts
// with time and has occasional shadows and bright spells (camera_model_lighting.hpp); optical blur and sensor noise
// come last. Everything is a function of the seed, the pose and the capture time: deterministic, and independent of
// how the simulation is stepped.
#include <cstdint>
#include <functional>
#include <vector>

#include <opencv2/core/mat.hpp>

#include "common/geometry.hpp"
#include "common/time.hpp"
#include "common/types.hpp"
#include "drivers/sim/sensors/camera_model_backdrop.hpp"
#include "drivers/sim/sensors/camera_model_config.hpp"
#include "drivers/sim/sensors/camera_model_lighting.hpp"
#include "drivers/sim/sensors/camera_model_scene.hpp"
#include "drivers/sim/sensors/sink.hpp"
#include "drivers/sim/world/world.hpp"

namespace fsd::sim {

// Ground truth of one cone in an image, for training and evaluating image classifiers and for tests.
struct ProjectedCone {
  int index = -1;  // into World::cones()
  ConeColour colour = ConeColour::Unknown;
  bool big = false;
  bool knocked = false;
  cv::Rect box;                   // pixels the cone's silhouette covers (occluders ignored), cut to the image
  bool truncated = false;         // the silhouette reaches past the image border
  double visible_fraction = 0.0;  // share of the silhouette's pixels not hidden by nearer objects
  double distance = 0.0;          // m from the optical centre to the cone's base centre
  cv::Point2d base_pixel;         // projection of the base centre (the paper's "bottom centre" for the homography)
};

class CameraModel {
 public:
  // `start` is the capture time of the first frame. The world must outlive the model.
  CameraModel(const CameraConfig& cfg, const World& world, std::uint64_t seed, Stamp start = 0.0);
  CameraModel(const CameraModel&) = delete;  // the scene refers to this object's sunlight
  CameraModel& operator=(const CameraModel&) = delete;

  // Captures every frame whose capture time is ≤ t and emits it JPEG-encoded, stamped capture time + latency.
  // body_pose_at(t) gives the vehicle body 3D pose (map ← body) at a capture time since the previous call.
  void advance_to(Stamp t, const std::function<Pose3(Stamp)>& body_pose_at, const ByteSink& sink);

  // The image (CV_8UC3, BGR) seen from this body pose with the lighting of capture time t.
  cv::Mat render(const Pose3& body_pose, Stamp t = 0.0) const;
  // The cones whose silhouette shows at least one pixel in the image from this pose, far to near.
  std::vector<ProjectedCone> visible_cones(const Pose3& body_pose) const;

  std::uint64_t frames_sent() const { return frames_; }
  Stamp next_capture() const { return start_ + static_cast<double>(frames_) / cfg_.rate; }
  const CameraConfig& config() const { return cfg_; }

 private:
  void render_into(const Pose3& body_pose, Stamp t, std::uint64_t noise_key, cv::Mat& out) const;
  void add_noise(std::uint64_t noise_key, cv::Mat& img) const;

  CameraConfig cfg_;
  const World& world_;
  std::uint64_t seed_;
  Stamp start_;
  Sunlight sun_;
  Backdrop backdrop_;
  SceneBuilder scene_;
  cv::Mat noise_up_, noise_down_;  // sensor noise bank, split in its positive and negative parts
  std::uint64_t frames_ = 0;
  cv::Mat frame_;
  std::vector<std::uint8_t> jpeg_;
};

}  // namespace fsd::sim
