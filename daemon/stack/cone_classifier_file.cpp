#include "daemon/stack/cone_classifier_file.hpp"

#include <fstream>
#include <iterator>
#include <string>

namespace fsd {

ConeClassifierModel load_cone_classifier_model(const std::filesystem::path& file) {
  const std::string name = file.string();
  std::error_code ec;
  const auto size = std::filesystem::file_size(file, ec);
  if (ec)
    throw ClassifierModelError(name + ": cannot read the classifier model (" + ec.message() +
                               "); train one with fsd train-classifier or set perception.camera.classifier.model");
  if (size > kMaxClassifierModelBytes)
    throw ClassifierModelError(name + ": " + std::to_string(size) + " bytes, more than a model can be");
  std::ifstream in(file, std::ios::binary);
  if (!in) throw ClassifierModelError(name + ": cannot open the classifier model");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  return parse_cone_classifier_model(text, name);
}

void save_cone_classifier_model(const ConeClassifierModel& model, const std::filesystem::path& file) {
  const std::filesystem::path tmp = file.string() + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw ClassifierModelError(file.string() + ": cannot write (" + tmp.string() + " does not open)");
    out << to_text(model);
    if (!out.flush()) throw ClassifierModelError(file.string() + ": write failed");
  }
  std::error_code ec;
  std::filesystem::rename(tmp, file, ec);
  if (ec) {
    std::filesystem::remove(tmp, ec);
    throw ClassifierModelError(file.string() + ": cannot replace the file: " + ec.message());
  }
}

}  // namespace fsd
