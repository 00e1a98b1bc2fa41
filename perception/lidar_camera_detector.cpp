#include "perception/lidar_camera_detector.hpp"

#include <cmath>
#include <numbers>
#include <vector>

namespace fsd {

LidarCameraDetector::LidarCameraDetector(const LidarDetectorConfig& lidar, const Pose3& body_from_lidar,
                                         std::unique_ptr<CameraStage> camera, double max_camera_gap)
    : lidar_(lidar, body_from_lidar), camera_(std::move(camera)), max_camera_gap_(max_camera_gap) {}

LidarDetection LidarCameraDetector::detect(const Scan& scan, const BodyPoseAt& pose_at, const CameraImage* image) {
  LidarDetection det = lidar_.detect(scan, pose_at);
  ++counters_.scans;
  if (!camera_) return det;
  if (!image || !(std::abs(image->capture - det.detections.stamp) <= max_camera_gap_)) {
    ++counters_.no_recent_frame;
    return det;
  }
  verify_with_camera(*camera_, det, pose_at, *image, lidar_.config().size.beam_spacing_deg * std::numbers::pi / 180.0);
  ++counters_.camera_frames_used;
  counters_.camera = camera_->stats();
  return det;
}

void verify_with_camera(CameraStage& camera, LidarDetection& det, const BodyPoseAt& pose_at, const CameraImage& image,
                        double beam_spacing_rad) {
  const double big_height = camera.colour().config().big_cone_height;
  auto& cones = det.detections.cones;
  if (cones.empty()) return;
  // vehicle(capture) ← vehicle(scan): the car moved between the two instants.
  Pose3 capture_from_scan = Pose3::Identity();
  if (pose_at) capture_from_scan = pose_at(image.capture).inverse() * pose_at(det.detections.stamp);

  std::vector<Cone> seen;
  std::vector<CandidateSize> sizes;
  seen.reserve(cones.size());
  sizes.reserve(cones.size());
  for (std::size_t i = 0; i < cones.size(); ++i) {
    Cone c = cones[i];
    c.id = static_cast<std::uint32_t>(i + 1);  // a tag to find the verdict again: the stage drops the rejected
    c.position = capture_from_scan * c.position;
    seen.push_back(c);
    const ConeCandidate* cand = i < det.candidates.size() ? &det.candidates[i] : nullptr;
    CandidateSize size;
    if (cand) {
      const double gap = cand->range * std::tan(beam_spacing_rad);
      const bool decisive = cand->height >= big_height || cand->height + gap < big_height;
      size = CandidateSize{decisive ? cand->height : 0.0, cand->width};
    }
    sizes.push_back(size);
  }
  camera.verify(seen, image.bgr, sizes);

  std::vector<Cone> kept;
  std::vector<ConeCandidate> kept_candidates;
  kept.reserve(seen.size());
  std::vector<bool> survived(cones.size(), false);
  for (const Cone& v : seen) survived[v.id - 1] = true;
  for (std::size_t i = 0; i < cones.size(); ++i)
    if (!survived[i]) det.camera_rejected.push_back(cones[i]);
  for (const Cone& v : seen) {
    const std::size_t i = v.id - 1;
    Cone c = cones[i];
    if (v.stage == DetectionStage::Camera) {
      c.stage = DetectionStage::Camera;
      if (v.colour != ConeColour::Unknown || c.colour_source != ColourSource::LidarIntensity) {
        c.colour = v.colour;
        c.colour_confidence = v.colour_confidence;
        c.colour_source = v.colour_source;
      }
    }
    kept.push_back(c);
    if (i < det.candidates.size()) kept_candidates.push_back(std::move(det.candidates[i]));
  }
  cones = std::move(kept);
  if (!det.candidates.empty()) det.candidates = std::move(kept_candidates);
}

}  // namespace fsd
