#include "perception/camera/classifier_training.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include <opencv2/ml.hpp>

namespace fsd {

void FeatureSet::add(const cv::Mat& roi_bgr, bool cone) {
  hog_.compute(roi_bgr, row_);
  features_.push_back(cv::Mat(1, static_cast<int>(row_.size()), CV_32F, row_.data()));
  labels_.push_back(cone ? 1 : 0);
}

std::size_t FeatureSet::count(bool cone) const {
  return static_cast<std::size_t>(std::count(labels_.begin(), labels_.end(), cone ? 1 : 0));
}

ConeClassifierModel train_cone_classifier(const FeatureSet& samples, const ClassifierTrainingConfig& cfg) {
  const std::size_t cones = samples.count(true), others = samples.count(false);
  if (cones == 0 || others == 0)
    throw std::invalid_argument("classifier training needs cones and non-cones (got " + std::to_string(cones) +
                                " and " + std::to_string(others) + ")");
  auto svm = cv::ml::SVM::create();
  svm->setType(cv::ml::SVM::C_SVC);
  svm->setKernel(cv::ml::SVM::LINEAR);
  svm->setC(cfg.c);
  svm->setTermCriteria(
      cv::TermCriteria(cv::TermCriteria::MAX_ITER | cv::TermCriteria::EPS, cfg.max_iterations, cfg.epsilon));
  if (cfg.balance_classes) {
    // Weights of the classes in label order (0: not a cone, 1: cone).
    const double n = static_cast<double>(samples.size());
    svm->setClassWeights((cv::Mat_<double>(2, 1) << n / (2.0 * others), n / (2.0 * cones)));
  }
  const cv::Mat labels(samples.labels(), true);
  svm->train(samples.features(), cv::ml::ROW_SAMPLE, labels);

  // A linear SVM is compressed to one support vector: decision d(x) = α·sv·x − ρ. OpenCV labels d > 0 with the
  // first class (0: not a cone), so the cone score is −d(x).
  const cv::Mat sv = svm->getSupportVectors();
  cv::Mat alpha, index;
  const double rho = svm->getDecisionFunction(0, alpha, index);
  if (sv.rows != 1 || alpha.total() != 1) throw std::logic_error("linear SVM did not compress to one support vector");
  const double a = alpha.at<double>(0);
  ConeClassifierModel model;
  model.hog = samples.hog().parameters();
  model.weights.resize(static_cast<std::size_t>(sv.cols));
  for (int i = 0; i < sv.cols; ++i) model.weights[static_cast<std::size_t>(i)] = -a * sv.at<float>(0, i);
  model.bias = rho;

  // The sign convention above is OpenCV's internal one: check it against the SVM's own labels.
  const ConeClassifier check(model);
  const cv::Mat& x = samples.features();
  for (int r = 0; r < std::min(x.rows, 200); ++r) {
    const double s = check.decision({x.ptr<float>(r), static_cast<std::size_t>(x.cols)});
    const bool cone = svm->predict(x.row(r)) > 0.5f;
    if (std::abs(s) > 1e-6 && (s > 0) != cone)
      throw std::logic_error("linear SVM: extracted weights disagree with cv::ml::SVM::predict");
  }
  return model;
}

double Confusion::accuracy() const {
  return total() ? static_cast<double>(cones_kept + others_rejected) / static_cast<double>(total()) : 0.0;
}
double Confusion::cone_recall() const {
  const std::size_t n = cones_kept + cones_rejected;
  return n ? static_cast<double>(cones_kept) / static_cast<double>(n) : 0.0;
}
double Confusion::rejection() const {
  const std::size_t n = others_rejected + others_kept;
  return n ? static_cast<double>(others_rejected) / static_cast<double>(n) : 0.0;
}
std::string Confusion::summary() const {
  char line[256];
  std::snprintf(
      line, sizeof line,
      "accuracy %.2f %% of %zu: cones kept %zu, cones rejected %zu, non-cones rejected %zu, non-cones kept %zu "
      "(cone recall %.2f %%, rejection %.2f %%)",
      100 * accuracy(), total(), cones_kept, cones_rejected, others_rejected, others_kept, 100 * cone_recall(),
      100 * rejection());
  return line;
}

Confusion evaluate(const ConeClassifier& classifier, const FeatureSet& samples) {
  Confusion c;
  const cv::Mat& x = samples.features();
  for (int r = 0; r < x.rows; ++r) {
    const bool kept = classifier.accepts(classifier.decision({x.ptr<float>(r), static_cast<std::size_t>(x.cols)}));
    if (samples.labels()[static_cast<std::size_t>(r)] == 1)
      ++(kept ? c.cones_kept : c.cones_rejected);
    else
      ++(kept ? c.others_kept : c.others_rejected);
  }
  return c;
}

}  // namespace fsd
