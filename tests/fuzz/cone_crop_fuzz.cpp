// libFuzzer target for the image files a user hands to `fsd classify` and `fsd train-classifier --real`
// (drivers/camera/image_file: PNG/JPEG header checks, then OpenCV's decoder) and the camera stages on the decoded
// crop (perception/camera: HOG + SVM, colour). Invariants beyond "no crash": a decoded image is 8-bit BGR within the
// header limits; the score is finite, the confidence in [0, 1], the colour a known one.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <span>

#include <opencv2/core.hpp>

#include "drivers/camera/image_file.hpp"
#include "perception/camera/camera_stage.hpp"

namespace {

void check(bool ok) {
  if (!ok) std::abort();
}

// A fixed model (no file to read): small weights of alternating sign, so scores vary with the features.
const fsd::ConeClassifier& classifier() {
  static const fsd::ConeClassifier c = [] {
    fsd::ConeClassifierModel m;
    m.weights.resize(m.hog.descriptor_size());
    for (std::size_t i = 0; i < m.weights.size(); ++i)
      m.weights[i] = (i % 2 ? 0.01 : -0.01) * static_cast<double>(i % 7);
    m.bias = 0.1;
    return fsd::ConeClassifier(m);
  }();
  return c;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  cv::setNumThreads(0);
  cv::Mat img;
  try {
    img = fsd::decode_image(std::span<const std::uint8_t>(data, size), "fuzz");
  } catch (const fsd::ImageFileError&) {
    return 0;
  }
  check(img.type() == CV_8UC3 && img.cols > 0 && img.rows > 0);
  check(img.cols <= fsd::kMaxImageSide && img.rows <= fsd::kMaxImageSide);
  if (img.cols < 2 || img.rows < 2 || img.total() > 512 * 512) return 0;  // keep executions fast
  static const fsd::ConeColourClassifier colour;
  const fsd::CropVerdict v = fsd::classify_crop(classifier(), colour, img);
  check(std::isfinite(v.score) && v.cone == (v.score >= 0.0));
  check(v.colour.confidence >= 0.0 && v.colour.confidence <= 1.0);
  check(static_cast<int>(v.colour.colour) <= static_cast<int>(fsd::ConeColour::Red));
  check(v.colour.colour == fsd::ConeColour::Unknown || v.colour.colour == v.colour.best);
  return 0;
}
