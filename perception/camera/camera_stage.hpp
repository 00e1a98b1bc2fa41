#pragma once
// The camera half of perception (DESIGN.md §3 and §5b, the paper's §III.B): LiDAR cone candidates of one camera
// frame are projected into the image (cone_projection.hpp), each ROI is verified by HOG + linear SVM
// (cone_classifier.hpp) and a verified cone gets its colour from HSV k-means (cone_colour.hpp).
//
// Contract with the LiDAR stages: candidates are fsd::Cone in the vehicle frame (position = the cluster's centroid
// on the ground, `points`, stage = DetectionStage::Lidar), optionally with the cluster's size. verify() then
//   - removes rejected candidates (not cones: tyres, stacks, posts, fences, ground), counted;
//   - marks accepted ones stage = Camera with colour, colour_confidence and colour_source = Camera (colour Unknown
//     when unsure);
//   - leaves candidates it cannot see (behind the camera, outside the image, too far to judge, mostly hidden behind
//     a nearer candidate: occlusion.hpp, whose ROI shows that one's pixels) untouched: still stage = Lidar,
//     unverified, with the LiDAR's colour;
//   - leaves every candidate untouched when the frame is unusable (empty, not 8-bit BGR), counted as a bad frame.
// Pure: no I/O, no clock, no threads of its own (OpenCV's parallel loops follow cv::setNumThreads).
#include <cstdint>
#include <span>
#include <vector>

#include <opencv2/core/mat.hpp>

#include "common/camera_geometry.hpp"
#include "common/config.hpp"
#include "common/types.hpp"
#include "perception/camera/cone_classifier.hpp"
#include "perception/camera/cone_colour.hpp"
#include "perception/camera/cone_projection.hpp"

namespace fsd {

struct CameraStageConfig {
  ConeProjectionConfig projection;
  ConeClassifierConfig classifier;
  ConeColourConfig colour;
};
// Keys under perception.camera.{projection,classifier,colour}.
void describe_camera_stage(ConfigSchema& schema);
CameraStageConfig read_camera_stage_config(const Config& cfg);

// The LiDAR cluster's envelope, when known (0 = unknown): the height tells a big orange cone from a small one.
struct CandidateSize {
  double height = 0.0;  // m, top of the cluster above the ground
  double width = 0.0;   // m
};

struct CameraStageStats {
  std::uint64_t frames = 0;
  std::uint64_t bad_frames = 0;      // unusable images: their candidates stayed unverified
  std::uint64_t candidates = 0;      // LiDAR candidates offered with usable frames
  std::uint64_t outside = 0;         // left unverified: not (enough) in the image
  std::uint64_t too_small = 0;       // left unverified: ROI too small to judge (far away)
  std::uint64_t hidden = 0;          // left unverified: mostly hidden behind a nearer candidate
  std::uint64_t rejected = 0;        // removed: not a cone
  std::uint64_t verified = 0;        // accepted as cones
  std::uint64_t colour_unknown = 0;  // accepted, colour Unknown
};

struct CameraFrameResult {
  bool frame_ok = false;
  int verified = 0, rejected = 0, unverified = 0;
};

// What `fsd classify` reports for one crop.
struct CropVerdict {
  bool cone = false;
  double score = 0.0;  // SVM decision value
  ColourResult colour;
};

class CameraStage {
 public:
  // Throws std::invalid_argument (projection) or ClassifierModelError (model) when they cannot work together.
  CameraStage(const CameraCalibration& calibration, ConeClassifierModel model, const CameraStageConfig& cfg = {});

  // `sizes` is empty or has one entry per candidate (std::invalid_argument otherwise).
  CameraFrameResult verify(std::vector<Cone>& candidates, const cv::Mat& bgr,
                           std::span<const CandidateSize> sizes = {});

  const CameraStageStats& stats() const { return stats_; }
  const ConeProjector& projector() const { return projector_; }
  const ConeClassifier& classifier() const { return classifier_; }
  const ConeColourClassifier& colour() const { return colour_; }

 private:
  ConeProjector projector_;
  ConeClassifier classifier_;
  ConeColourClassifier colour_;
  CameraStageStats stats_;
};

// The camera stages on one crop that a cone fills (`fsd classify`): HOG + SVM on the whole crop, colour with the
// crop's silhouette prior. `bgr`: CV_8UC3, at least 2 × 2 pixels (std::invalid_argument otherwise).
CropVerdict classify_crop(const ConeClassifier& classifier, const ConeColourClassifier& colour, const cv::Mat& bgr);

// The ROI's pixels; where it reaches past the image border the border is replicated, so the cone keeps its place
// in the ROI. One cut for the stage and for training, so the classifier sees what it was trained on.
cv::Mat cut_roi(const cv::Mat& image, const CandidateRoi& roi);
// Where the candidate's base lies in cut_roi()'s pixels, and the scale.
ConeView roi_view(const CandidateRoi& roi);

}  // namespace fsd
