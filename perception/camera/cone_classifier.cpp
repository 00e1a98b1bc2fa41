#include "perception/camera/cone_classifier.hpp"

#include <cmath>

#include "common/json_fields.hpp"

namespace fsd {

const ConfigSection<ConeClassifierConfig>& cone_classifier_section() {
  static const auto s =
      ConfigSection<ConeClassifierConfig>("perception.camera.classifier")
          .string("model", &ConeClassifierConfig::model, {},
                  "HOG + linear SVM model file (fsd train-classifier writes it), relative to the working directory.")
          .number("min_score", &ConeClassifierConfig::min_score, -5.0, 5.0, "",
                  "SVM decision value at and above which a candidate's ROI is a cone (higher: fewer false cones, "
                  "more cones rejected).",
                  true);
  return s;
}

namespace {
using json = nlohmann::json;
using Fields = JsonFields<ClassifierModelError>;

constexpr const char* kFormat = "fsd-cone-classifier";
constexpr int kVersion = 1;
constexpr double kMaxWeight = 1e6;  // a linear SVM on normalised HOG features has weights of order 1

HogParameters read_hog(const Fields& f) {
  f.only({"window", "block", "stride", "cell", "bins"});
  const auto window = f.integers("window", f.at("window"), 1, 4096);
  if (window.size() != 2) f.fail("window", "expected [width, height]");
  HogParameters p;
  p.window_width = window[0];
  p.window_height = window[1];
  p.block = f.integer("block", 1, 4096);
  p.stride = f.integer("stride", 1, 4096);
  p.cell = f.integer("cell", 1, 4096);
  p.bins = f.integer("bins", 1, 4096);
  if (const std::string problem = p.check(); !problem.empty()) f.fail("", problem);
  return p;
}
}  // namespace

ConeClassifierModel parse_cone_classifier_model(const std::string& text, const std::string& origin) {
  if (text.size() > kMaxClassifierModelBytes)
    throw ClassifierModelError(origin + ": " + std::to_string(text.size()) + " bytes, more than a model can be (" +
                               std::to_string(kMaxClassifierModelBytes) + ")");
  json j;
  try {
    j = json::parse(text);
  } catch (const json::exception& e) {  // parse_error, and out_of_range for a number like 1e999
    throw ClassifierModelError(origin + ": not valid JSON: " + e.what());
  }
  const Fields f(j, origin, "");
  f.only({"format", "version", "hog", "svm", "training"});
  if (f.string("format") != kFormat) f.fail("format", std::string("expected \"") + kFormat + "\"");
  if (f.integer("version", 0, 1000) != kVersion)
    f.fail("version", "unsupported version; this build reads version " + std::to_string(kVersion));
  ConeClassifierModel m;
  m.hog = read_hog(f.object("hog"));
  const Fields svm = f.object("svm");
  svm.only({"weights", "bias"});
  m.weights = svm.numbers("weights", svm.at("weights"), -kMaxWeight, kMaxWeight);
  if (m.weights.size() != m.hog.descriptor_size())
    svm.fail("weights", "has " + std::to_string(m.weights.size()) + " values, the HOG geometry gives " +
                            std::to_string(m.hog.descriptor_size()) + " features");
  m.bias = svm.number("bias", -kMaxWeight, kMaxWeight);
  if (f.has("training")) {
    if (!f.at("training").is_object()) f.fail("training", "expected an object");
    m.training = f.at("training");
  }
  return m;
}

std::string to_text(const ConeClassifierModel& m) {
  const json j = {{"format", kFormat},
                  {"version", kVersion},
                  {"hog",
                   {{"window", {m.hog.window_width, m.hog.window_height}},
                    {"block", m.hog.block},
                    {"stride", m.hog.stride},
                    {"cell", m.hog.cell},
                    {"bins", m.hog.bins}}},
                  {"svm", {{"weights", m.weights}, {"bias", m.bias}}},
                  {"training", m.training}};
  return j.dump(1) + "\n";
}

ConeClassifier::ConeClassifier(ConeClassifierModel model, const ConeClassifierConfig& cfg)
    : model_(std::move(model)), cfg_(cfg), hog_(model_.hog) {
  if (model_.weights.size() != hog_.size())
    throw ClassifierModelError("classifier model: " + std::to_string(model_.weights.size()) + " weights for " +
                               std::to_string(hog_.size()) + " HOG features");
}

double ConeClassifier::score(const cv::Mat& roi_bgr) const {
  std::vector<float> x;
  hog_.compute(roi_bgr, x);
  return decision(x);
}

double ConeClassifier::decision(std::span<const float> features) const {
  if (features.size() != model_.weights.size())
    throw std::invalid_argument("classifier: " + std::to_string(features.size()) + " features for " +
                                std::to_string(model_.weights.size()) + " weights");
  double s = model_.bias;
  for (std::size_t i = 0; i < features.size(); ++i) s += model_.weights[i] * static_cast<double>(features[i]);
  return s;
}

}  // namespace fsd
