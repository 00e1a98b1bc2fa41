// `fsd classify --image FILE [--json]`: the camera stages on one crop of a cone (DESIGN.md §9): HOG + SVM says cone
// or not with its score, the colour stage names the colour with its confidence. The crop is the whole image.
#include <cstdio>
#include <iostream>
#include <string>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "daemon/cli/cli.hpp"
#include "daemon/cli/commands.hpp"
#include "daemon/stack/cone_classifier_file.hpp"
#include "daemon/stack/settings.hpp"
#include "drivers/camera/image_file.hpp"
#include "perception/camera/camera_stage.hpp"

namespace fsd {

namespace {
struct ClassifyArgs {
  std::string image, config;
  bool json = false;
};

int classify(const ClassifyArgs& a) {
  const Config cfg = a.config.empty() ? Config(config_schema()) : Config::load(config_schema(), a.config);
  const CameraStageConfig stage = read_camera_stage_config(cfg);
  try {
    const ConeClassifier classifier(load_cone_classifier_model(stage.classifier.model), stage.classifier);
    const ConeColourClassifier colour(stage.colour);
    const cv::Mat crop = read_image_file(a.image);
    if (crop.cols < 2 || crop.rows < 2) {
      std::cerr << "fsd classify: " << a.image << ": " << crop.cols << " x " << crop.rows
                << " px is too small for a crop (at least 2 x 2)\n";
      return kExitBadInput;
    }
    const CropVerdict v = classify_crop(classifier, colour, crop);
    const std::string name(to_string(v.colour.colour));
    if (a.json) {
      const nlohmann::json out = {
          {"cone", v.cone}, {"score", v.score}, {"colour", name}, {"confidence", v.colour.confidence}};
      std::cout << out.dump() << "\n";
    } else {
      std::printf("%s: %s (SVM score %+.3f), colour %s (confidence %.2f)\n", a.image.c_str(),
                  v.cone ? "cone" : "not a cone", v.score, name.c_str(), v.colour.confidence);
    }
    return kExitOk;
  } catch (const ClassifierModelError& e) {
    std::cerr << "fsd classify: " << e.what() << "\n";
  } catch (const ImageFileError& e) {
    std::cerr << "fsd classify: " << e.what() << "\n";
  }
  return kExitBadInput;
}
}  // namespace

void add_classify_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand(
      "classify", "Camera stages on one cone crop (PNG or JPEG): cone or not (HOG + linear SVM) and its colour");
  static ClassifyArgs args;
  cmd->add_option("--image", args.image, "the crop: an image the cone fills (PNG or JPEG)")->required();
  cmd->add_flag("--json", args.json, "print {\"cone\", \"score\", \"colour\", \"confidence\"} as one JSON object");
  cmd->add_option(
      "--config", args.config,
      "configuration file (perception.camera.*: the model file, thresholds); default: compiled-in defaults");
  cmd->callback([&exit_code] { exit_code = classify(args); });
}

}  // namespace fsd
