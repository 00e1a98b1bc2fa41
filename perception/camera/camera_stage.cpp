#include "perception/camera/camera_stage.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

#include <opencv2/core.hpp>

#include "perception/camera/occlusion.hpp"

namespace fsd {

void describe_camera_stage(ConfigSchema& schema) {
  cone_projection_section().describe(schema);
  cone_classifier_section().describe(schema);
  cone_colour_section().describe(schema);
}

CameraStageConfig read_camera_stage_config(const Config& cfg) {
  return {cone_projection_section().read(cfg), cone_classifier_section().read(cfg), cone_colour_section().read(cfg)};
}

cv::Mat cut_roi(const cv::Mat& image, const CandidateRoi& roi) {
  const cv::Rect all(0, 0, image.cols, image.rows);
  const cv::Rect inside = roi.pixels & all;
  if (inside.area() == 0) return {};
  if (inside == roi.pixels) return image(inside);
  cv::Mat out;
  cv::copyMakeBorder(image(inside), out, inside.y - roi.pixels.y, roi.pixels.br().y - inside.br().y,
                     inside.x - roi.pixels.x, roi.pixels.br().x - inside.br().x, cv::BORDER_REPLICATE);
  return out;
}

ConeView roi_view(const CandidateRoi& roi) {
  return {cv::Point2d(roi.base.x - roi.pixels.x, roi.base.y - roi.pixels.y), roi.px_per_m};
}

CropVerdict classify_crop(const ConeClassifier& classifier, const ConeColourClassifier& colour, const cv::Mat& bgr) {
  if (bgr.type() != CV_8UC3 || bgr.cols < 2 || bgr.rows < 2)
    throw std::invalid_argument("a cone crop must be an 8-bit colour image of at least 2 x 2 pixels");
  CropVerdict v;
  v.score = classifier.score(bgr);
  v.cone = classifier.accepts(v.score);
  v.colour = colour.classify(bgr, ConeColourClassifier::crop_view(bgr.size()));
  return v;
}

namespace {

// The other candidates in the image, each as large as the LiDAR measured it and at least as wide as the rules'
// cone of that height (the LiDAR sees a cone's near side only), in the image's pixels: those nearer to the car than
// candidate i and those farther.
struct Others {
  std::vector<ImageSilhouette> in_front, behind;
};

Others others_of(std::size_t i, const std::vector<Cone>& candidates, const std::vector<CandidateRoi>& rois,
                 std::span<const CandidateSize> sizes) {
  const double range = candidates[i].position.head<2>().norm();
  Others out;
  for (std::size_t j = 0; j < candidates.size(); ++j) {
    if (j == i || rois[j].status == RoiStatus::Outside || !(rois[j].px_per_m > 0)) continue;
    const double h = !sizes.empty() && sizes[j].height > 0 ? sizes[j].height : kSmallConeHeight;
    const double hw = std::max(!sizes.empty() && sizes[j].width > 0 ? sizes[j].width / 2 : 0.0,
                               h >= kBigConeMinLidarHeight ? kBigConeHalfWidth : kSmallConeHalfWidth);
    (candidates[j].position.head<2>().norm() < range ? out.in_front : out.behind)
        .push_back({rois[j].base, rois[j].px_per_m, hw, h});
  }
  return out;
}

}  // namespace

CameraStage::CameraStage(const CameraCalibration& calibration, ConeClassifierModel model, const CameraStageConfig& cfg)
    : projector_(calibration, cfg.projection), classifier_(std::move(model), cfg.classifier), colour_(cfg.colour) {}

CameraFrameResult CameraStage::verify(std::vector<Cone>& candidates, const cv::Mat& bgr,
                                      std::span<const CandidateSize> sizes) {
  if (!sizes.empty() && sizes.size() != candidates.size())
    throw std::invalid_argument("camera stage: " + std::to_string(sizes.size()) + " sizes for " +
                                std::to_string(candidates.size()) + " candidates");
  CameraFrameResult result;
  ++stats_.frames;
  if (bgr.empty() || bgr.type() != CV_8UC3 || bgr.cols < 2 || bgr.rows < 2) {
    ++stats_.bad_frames;
    result.unverified = static_cast<int>(candidates.size());
    return result;
  }
  result.frame_ok = true;

  // Every candidate's place in the image first: a nearer one may hide part of a farther one.
  std::vector<CandidateRoi> rois(candidates.size());
  for (std::size_t i = 0; i < candidates.size(); ++i)
    if (candidates[i].stage == DetectionStage::Lidar) rois[i] = projector_.project(candidates[i].position, bgr.size());

  std::vector<Cone> kept;
  kept.reserve(candidates.size());
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    Cone& c = candidates[i];
    if (c.stage != DetectionStage::Lidar) {  // not a LiDAR candidate: not ours to judge
      kept.push_back(c);
      continue;
    }
    ++stats_.candidates;
    const CandidateRoi& roi = rois[i];
    if (roi.status != RoiStatus::Inside) {
      ++(roi.status == RoiStatus::TooSmall ? stats_.too_small : stats_.outside);
      ++result.unverified;
      kept.push_back(c);
      continue;
    }
    // Mostly hidden behind nearer candidates, its ROI shows theirs: neither a verdict nor a colour. Partly hidden,
    // its colour is judged on the part that shows.
    Others others = others_of(i, candidates, rois, sizes);
    if (hidden_share(roi.base, roi.px_per_m, others.in_front) > colour_.config().max_hidden) {
      ++stats_.hidden;
      ++result.unverified;
      kept.push_back(c);
      continue;
    }
    const cv::Mat pixels = cut_roi(bgr, roi);
    if (!classifier_.accepts(classifier_.score(pixels))) {
      ++stats_.rejected;
      ++result.rejected;
      continue;
    }
    for (auto* list : {&others.in_front, &others.behind})
      for (auto& o : *list) o.base -= cv::Point2d(roi.pixels.x, roi.pixels.y);  // into the ROI's pixels
    const ColourResult colour =
        colour_.classify(pixels, roi_view(roi), sizes.empty() ? 0.0 : sizes[i].height, others.in_front, others.behind);
    c.stage = DetectionStage::Camera;
    c.colour = colour.colour;
    c.colour_confidence = colour.confidence;
    c.colour_source = ColourSource::Camera;
    if (colour.colour == ConeColour::Unknown) ++stats_.colour_unknown;
    ++stats_.verified;
    ++result.verified;
    kept.push_back(c);
  }
  candidates = std::move(kept);
  return result;
}

}  // namespace fsd
