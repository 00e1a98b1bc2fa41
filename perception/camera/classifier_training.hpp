#pragma once
// Training the camera's cone classifier (the paper's §III.B.2, "we build the dataset of the cones and train the
// model using OpenCV tools"): HOG features of labelled ROIs, a linear C-SVM from cv::ml::SVM, and the confusion of a
// model on held-back samples. Deterministic: the same samples in the same order give the same model.
// Where the samples come from (the virtual car's camera, a folder of real crops) is the daemon's business
// (daemon/cli/classifier_training_set.hpp, `fsd train-classifier`).
#include <cstddef>
#include <string>
#include <vector>

#include <opencv2/core/mat.hpp>

#include "perception/camera/cone_classifier.hpp"
#include "perception/camera/hog_features.hpp"

namespace fsd {

// HOG feature rows and labels, filled sample by sample.
class FeatureSet {
 public:
  explicit FeatureSet(const HogParameters& hog = {}) : hog_(hog) {}
  void add(const cv::Mat& roi_bgr, bool cone);
  std::size_t size() const { return labels_.size(); }
  std::size_t count(bool cone) const;
  const cv::Mat& features() const { return features_; }       // CV_32F, one row per sample
  const std::vector<int>& labels() const { return labels_; }  // 1 cone, 0 not a cone
  const HogFeatures& hog() const { return hog_; }

 private:
  HogFeatures hog_;
  cv::Mat features_;
  std::vector<int> labels_;
  std::vector<float> row_;
};

struct ClassifierTrainingConfig {
  double c = 0.1;               // soft-margin penalty of the C-SVM
  int max_iterations = 200000;  // of the SVM solver
  double epsilon = 1e-5;        // its tolerance
  bool balance_classes = true;  // weigh each class by the inverse of its share, so neither dominates the margin
};

// Throws std::invalid_argument when either class has no sample.
ConeClassifierModel train_cone_classifier(const FeatureSet& samples, const ClassifierTrainingConfig& cfg = {});

struct Confusion {
  std::size_t cones_kept = 0, cones_rejected = 0;    // true cones: accepted / rejected
  std::size_t others_rejected = 0, others_kept = 0;  // not cones: rejected / accepted
  std::size_t total() const { return cones_kept + cones_rejected + others_rejected + others_kept; }
  double accuracy() const;
  double cone_recall() const;   // share of cones kept
  double rejection() const;     // share of non-cones rejected
  std::string summary() const;  // one line: accuracy and the four counts
};

Confusion evaluate(const ConeClassifier& classifier, const FeatureSet& samples);

}  // namespace fsd
