#pragma once
// The camera classifier's model file (perception/camera/cone_classifier.hpp has the format): read by the daemon and
// `fsd classify` at the path of perception.camera.classifier.model, written by `fsd train-classifier`.
#include <filesystem>

#include "perception/camera/cone_classifier.hpp"

namespace fsd {

// Throws ClassifierModelError naming the file: missing, unreadable, too large, or not a valid model.
ConeClassifierModel load_cone_classifier_model(const std::filesystem::path& file);
// Writes the file whole or not at all (temporary file, then rename). Throws ClassifierModelError.
void save_cone_classifier_model(const ConeClassifierModel& model, const std::filesystem::path& file);

}  // namespace fsd
