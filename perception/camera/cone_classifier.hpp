#pragma once
// Camera stage 2 (DESIGN.md §5b, the paper's §III.B.2): cone or not, from HOG features of the ROI and a linear SVM.
// The model is what cv::ml::SVM learns with a linear kernel, one weight per feature and a bias
// (classifier_training.hpp trains it); the score is the SVM's decision value w·x + b, positive for a cone.
//
// The model file is JSON (perception/models/cone_hog_svm.json, docs/perception.md), parsed strictly like the camera
// calibration: every error names the origin and the field.
//   { "format": "fsd-cone-classifier", "version": 1,
//     "hog": { "window": [32, 48], "block": 16, "stride": 8, "cell": 8, "bins": 9 },
//     "svm": { "weights": [ ... one per feature ... ], "bias": -0.3 },
//     "training": { ... how it was made: seed, tracks, held-back accuracy ... } }
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <opencv2/core/mat.hpp>

#include "common/config.hpp"
#include "perception/camera/hog_features.hpp"

namespace fsd {

// Thrown for model text that is not a valid classifier; what() names the origin and the field.
class ClassifierModelError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct ConeClassifierModel {
  HogParameters hog;
  std::vector<double> weights;                         // one per HOG feature
  double bias = 0.0;                                   // score = weights · features + bias; positive: a cone
  nlohmann::json training = nlohmann::json::object();  // provenance, not used for classifying
};

inline constexpr std::size_t kMaxClassifierModelBytes = 16u << 20;

// `origin` names the source (a file) in error messages.
ConeClassifierModel parse_cone_classifier_model(const std::string& text, const std::string& origin);
std::string to_text(const ConeClassifierModel& model);  // the file's bytes: the same model gives the same text

struct ConeClassifierConfig {
  // Model file, relative to the working directory (the checkout; installed: /usr/local/share/fsd/models). The
  // daemon reads it; the classifier takes the parsed model.
  std::string model = "perception/models/cone_hog_svm.json";
  double min_score = 0.0;  // SVM decision value at and above which an ROI is a cone
};
const ConfigSection<ConeClassifierConfig>& cone_classifier_section();  // prefix "perception.camera.classifier"

class ConeClassifier {
 public:
  // Throws ClassifierModelError for a model whose weights do not fit its HOG geometry.
  explicit ConeClassifier(ConeClassifierModel model, const ConeClassifierConfig& cfg = {});

  // The SVM's decision value for an ROI (CV_8UC3 BGR, any size): positive is a cone.
  double score(const cv::Mat& roi_bgr) const;
  // The decision value of HOG features already computed (one per weight).
  double decision(std::span<const float> features) const;
  bool accepts(double score) const { return score >= cfg_.min_score; }

  const ConeClassifierModel& model() const { return model_; }
  const HogFeatures& features() const { return hog_; }

 private:
  ConeClassifierModel model_;
  ConeClassifierConfig cfg_;
  HogFeatures hog_;
};

}  // namespace fsd
