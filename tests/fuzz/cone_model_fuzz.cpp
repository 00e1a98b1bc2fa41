// libFuzzer target for the camera classifier's model file (perception/camera/cone_classifier: JSON with the HOG
// geometry and the SVM's weights), read by the daemon and `fsd classify`. Invariants beyond "no crash": an accepted
// model has one weight per HOG feature, writes out to text that parses to the same text, and scores a crop finitely.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include <opencv2/core.hpp>

#include "perception/camera/cone_classifier.hpp"

namespace {
void check(bool ok) {
  if (!ok) std::abort();
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  cv::setNumThreads(0);
  fsd::ConeClassifierModel m;
  try {
    m = fsd::parse_cone_classifier_model(std::string(reinterpret_cast<const char*>(data), size), "fuzz");
  } catch (const fsd::ClassifierModelError&) {
    return 0;
  }
  check(m.weights.size() == m.hog.descriptor_size() && m.hog.check().empty());
  const std::string text = fsd::to_text(m);
  check(fsd::to_text(fsd::parse_cone_classifier_model(text, "again")) == text);
  static const cv::Mat crop = [] {
    cv::Mat c(30, 20, CV_8UC3);
    cv::randu(c, 0, 255);
    return c;
  }();
  const fsd::ConeClassifier classifier(m);
  check(std::isfinite(classifier.score(crop)));
  return 0;
}
