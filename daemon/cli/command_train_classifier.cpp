// `fsd train-classifier`: the camera's HOG + linear SVM model from crops rendered by the virtual car's camera (cones
// of every colour, range and lighting; tyres, stacks, posts, fences, grass and asphalt), plus real crops from a
// folder; seeded, so the same arguments give the same model bytes. Prints the confusion on held-back crops.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "common/track.hpp"
#include "daemon/cli/classifier_training_set.hpp"
#include "daemon/cli/cli.hpp"
#include "daemon/cli/commands.hpp"
#include "daemon/stack/cone_classifier_file.hpp"
#include "drivers/camera/image_file.hpp"

namespace fsd {

namespace {
struct TrainArgs {
  std::string out = ConeClassifierConfig{}.model;
  std::vector<std::string> tracks{"../shared/tracks/epfl_track_1.csv",
                                  "../shared/tracks/epfl_track_3.csv",
                                  "../shared/tracks/epfl_fsds_competition_1.csv",
                                  "../shared/tracks/epfl_VSV.csv",
                                  "../shared/tracks/amz_fssim_thin.csv",
                                  "../shared/tracks/epfl_skidpad.csv",
                                  "../shared/tracks/epfl_acceleration.csv"};
  std::uint64_t seed = 1;
  int frames = 120;
  std::string real;
  double c = ClassifierTrainingConfig{}.c;
  double position_noise = 0.08;  // m: more than the LiDAR's, so the model tolerates cones off the ROI's centre
};

nlohmann::json metrics(const Confusion& c) {
  return {{"samples", c.total()},
          {"accuracy", c.accuracy()},
          {"cone_recall", c.cone_recall()},
          {"rejection", c.rejection()}};
}

int train(const TrainArgs& a) {
  try {
    TrainingSetConfig cfg;
    cfg.scenes.tracks = a.tracks;
    cfg.scenes.frames_per_track = a.frames;
    cfg.scenes.seed = a.seed;
    cfg.scenes.position_noise = a.position_noise;
    cfg.real_dir = a.real;
    std::printf("fsd train-classifier: %zu tracks x %d frames, seed %llu%s\n", a.tracks.size(), a.frames,
                static_cast<unsigned long long>(a.seed), a.real.empty() ? "" : (", real crops from " + a.real).c_str());
    const auto t0 = std::chrono::steady_clock::now();
    const TrainingSet set = build_training_set(cfg);
    std::printf("  training samples: %zu (%zu cones, %zu not cones)\n   ", set.train.size(), set.train.count(true),
                set.train.count(false));
    for (const auto& [kind, n] : set.kinds) std::printf(" %s %zu", kind.c_str(), n);
    std::printf("\n  held back: %zu rendered crops, %zu real crops\n", set.held_back.size(), set.real_held_back.size());

    ClassifierTrainingConfig training;
    training.c = a.c;
    ConeClassifierModel model = train_cone_classifier(set.train, training);
    const ConeClassifier classifier(model);
    const Confusion held = evaluate(classifier, set.held_back);
    std::printf("  held-back rendered crops: %s\n", held.summary().c_str());
    nlohmann::json provenance = {{"tool", "fsd train-classifier"},       {"seed", a.seed},
                                 {"frames_per_track", a.frames},         {"c", a.c},
                                 {"position_noise", a.position_noise},   {"tracks", nlohmann::json::array()},
                                 {"training_samples", set.train.size()}, {"held_back_rendered", metrics(held)}};
    for (const auto& t : a.tracks) provenance["tracks"].push_back(std::filesystem::path(t).stem().string());
    if (!a.real.empty()) {
      const Confusion real = evaluate(classifier, set.real_held_back);
      std::printf("  held-back real crops: %s\n", real.summary().c_str());
      provenance["real_crops_trained"] = set.real_train;
      provenance["held_back_real"] = metrics(real);
    }
    model.training = provenance;
    save_cone_classifier_model(model, a.out);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::printf("  model (%zu HOG weights) written to %s in %.1f s\n", model.weights.size(), a.out.c_str(), seconds);
    return kExitOk;
  } catch (const TrackError& e) {
    std::cerr << "fsd train-classifier: " << e.what() << "\n";
  } catch (const ImageFileError& e) {
    std::cerr << "fsd train-classifier: " << e.what() << "\n";
  } catch (const ClassifierModelError& e) {
    std::cerr << "fsd train-classifier: " << e.what() << "\n";
  } catch (const std::invalid_argument& e) {
    std::cerr << "fsd train-classifier: " << e.what() << "\n";
  }
  return kExitBadInput;
}
}  // namespace

void add_train_classifier_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand(
      "train-classifier",
      "Train the camera's HOG + linear SVM cone classifier on crops rendered by the virtual car's camera (and real "
      "crops from --real DIR); prints its accuracy on held-back crops");
  static TrainArgs args;
  cmd->add_option("--out", args.out, "model file to write")->capture_default_str();
  cmd->add_option("--track", args.tracks, "track files to render (repeat the option); default: seven shared tracks");
  cmd->add_option("--seed", args.seed, "seed of the worlds, cameras, poses and lighting")->capture_default_str();
  cmd->add_option("--frames", args.frames, "frames rendered per track")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  cmd->add_option("--real", args.real, "folder of real crops: DIR/cone/*.png|jpg and DIR/not_cone/*.png|jpg");
  cmd->add_option("--position-noise", args.position_noise,
                  "σ of the candidates' position error (m) in the rendered training crops")
      ->check(CLI::Range(0.0, 0.5))
      ->capture_default_str();
  cmd->add_option("--c", args.c, "soft-margin penalty C of the linear SVM")
      ->check(CLI::Range(1e-6, 1e6))
      ->capture_default_str();
  cmd->callback([&exit_code] { exit_code = train(args); });
}

}  // namespace fsd
