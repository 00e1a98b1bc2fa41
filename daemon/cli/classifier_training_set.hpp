#pragma once
// The samples of `fsd train-classifier`: ROIs cut from the virtual car's frames exactly as the camera stage cuts
// them (rendered_camera_scenes.hpp), and crops a user photographed (a folder with cone/ and not_cone/). A part of
// each is held back, never trained on, to measure the model.
//
// Rendered samples: each clean candidate's ROI (cones at least 70 % visible and not cut by the border; others not
// covered by a visible cone), and for training also the ROI mirrored and a tight crop of the object (cones: their
// silhouette with a random margin; others: their own size), so that crops a person cuts (`fsd classify`) look like
// what the model knows. Every fifth frame of each track is held back.
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "daemon/cli/rendered_camera_scenes.hpp"
#include "perception/camera/classifier_training.hpp"

namespace fsd {

struct TrainingSetConfig {
  RenderedScenesConfig scenes;
  int held_back_every = 5;         // frames (and real crops) k·N − 1 are held back
  std::filesystem::path real_dir;  // optional: real crops in real_dir/cone and real_dir/not_cone
};

struct TrainingSet {
  FeatureSet train, held_back;               // rendered (training also holds the real training crops)
  FeatureSet real_held_back;                 // real crops held back
  std::size_t real_train = 0;                // real crops trained on (mirrored ones not counted)
  std::map<std::string, std::size_t> kinds;  // training samples by kind (cone, tyre, ..., real_cone, real_not_cone)
};

// Throws TrackError for a track that does not load, ImageFileError for a real crop that is not a readable image,
// std::invalid_argument for a real_dir without its cone/ and not_cone/ folders.
TrainingSet build_training_set(const TrainingSetConfig& cfg);

// The rendered candidates of one frame that make clean samples, with their ROIs as the camera stage cuts them
// (for training and for judging the stage on frames it never saw).
struct CleanCandidate {
  const RenderedCandidate* candidate;
  CandidateRoi roi;
};
std::vector<CleanCandidate> clean_candidates(const RenderedFrame& frame, const ConeProjector& projector);

// The image files (PNG, JPEG) of a folder, sorted by name; throws std::invalid_argument when it is not a folder.
std::vector<std::filesystem::path> image_files(const std::filesystem::path& dir);

}  // namespace fsd
