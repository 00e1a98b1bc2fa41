// Speed of the camera stages (perception/camera/camera_stage.hpp) on frames of the virtual car's camera (640 x 480,
// default mount) with about 20 LiDAR candidates each (cones, tyres, stacks, posts, fence points, ground), the shipped
// model, on one core: OpenCV's own threads are switched off.
//   build/bench/camera_stage_bench
// BM_CameraStageVerify is one frame (items/s = frames/s); the naive peer BM_SlidingWindowHog runs the same HOG + SVM
// over the whole frame at every scale (cv::HOGDescriptor::detectMultiScale), what the camera would do without the
// LiDAR's candidates (the paper's reason for LiDAR-assisted ROIs).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/objdetect.hpp>

#include "daemon/cli/rendered_camera_scenes.hpp"
#include "daemon/stack/cone_classifier_file.hpp"

namespace {

using namespace fsd;

struct Frames {
  ConeClassifierModel model = load_cone_classifier_model("perception/models/cone_hog_svm.json");
  std::vector<RenderedFrame> frames;
  double candidates_per_frame = 0;

  Frames() {
    cv::setNumThreads(1);
    RenderedScenesConfig cfg;
    cfg.tracks = {"../shared/tracks/epfl_track_2.csv"};
    cfg.frames_per_track = 40;
    cfg.vary_camera = false;  // the default camera: 640 x 480, 70°
    cfg.seed = 7;
    cfg.max_range = 25.0;
    std::size_t n = 0;
    render_camera_scenes(cfg, [&](const RenderedFrame& f) {
      // About 20 candidates: the nearest ones within 25 m.
      RenderedFrame g = f;
      std::sort(g.candidates.begin(), g.candidates.end(),
                [](const auto& a, const auto& b) { return a.range < b.range; });
      if (g.candidates.size() > 20) g.candidates.resize(20);
      n += g.candidates.size();
      frames.push_back(std::move(g));
    });
    candidates_per_frame = static_cast<double>(n) / static_cast<double>(frames.size());
  }
};

Frames& frames() {
  static Frames f;
  return f;
}

void BM_CameraStageVerify(benchmark::State& state) {
  Frames& f = frames();
  CameraStage stage(f.frames[0].calibration, f.model);
  std::size_t i = 0;
  std::vector<Cone> cones;
  std::vector<CandidateSize> sizes;
  for (auto _ : state) {
    const RenderedFrame& frame = f.frames[i++ % f.frames.size()];
    cones.clear();
    sizes.clear();
    for (const auto& c : frame.candidates) cones.push_back(c.cone), sizes.push_back(c.size);
    const CameraFrameResult r = stage.verify(cones, frame.bgr, sizes);
    benchmark::DoNotOptimize(r);
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["candidates"] = f.candidates_per_frame;
  state.counters["verified_share"] = static_cast<double>(stage.stats().verified) /
                                     static_cast<double>(std::max<std::uint64_t>(1, stage.stats().candidates));
}
BENCHMARK(BM_CameraStageVerify)->Unit(benchmark::kMillisecond);

// The stages one by one on the frames' in-image candidates: per candidate.
void BM_ClassifierPerRoi(benchmark::State& state) {
  Frames& f = frames();
  const ConeClassifier classifier(f.model);
  const ConeProjector projector(f.frames[0].calibration);
  std::vector<cv::Mat> rois;
  for (const auto& frame : f.frames)
    for (const auto& c : frame.candidates)
      if (const auto roi = projector.project(c.cone.position, frame.bgr.size()); roi.status == RoiStatus::Inside)
        rois.push_back(cut_roi(frame.bgr, roi).clone());
  std::size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(classifier.score(rois[i++ % rois.size()]));
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_ClassifierPerRoi)->Unit(benchmark::kMicrosecond);

void BM_ColourPerRoi(benchmark::State& state) {
  Frames& f = frames();
  const ConeColourClassifier colour;
  const ConeProjector projector(f.frames[0].calibration);
  std::vector<std::pair<cv::Mat, ConeView>> rois;
  for (const auto& frame : f.frames)
    for (const auto& c : frame.candidates)
      if (const auto roi = projector.project(c.cone.position, frame.bgr.size());
          c.is_cone && roi.status == RoiStatus::Inside)
        rois.emplace_back(cut_roi(frame.bgr, roi).clone(), roi_view(roi));
  std::size_t i = 0;
  for (auto _ : state) {
    const auto& [img, view] = rois[i++ % rois.size()];
    benchmark::DoNotOptimize(colour.classify(img, view));
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_ColourPerRoi)->Unit(benchmark::kMicrosecond);

// Naive peer: the same HOG + linear SVM slid over the whole frame at every scale, without LiDAR candidates.
void BM_SlidingWindowHog(benchmark::State& state) {
  Frames& f = frames();
  const HogParameters& p = f.model.hog;
  cv::HOGDescriptor hog(cv::Size(p.window_width, p.window_height), cv::Size(p.block, p.block),
                        cv::Size(p.stride, p.stride), cv::Size(p.cell, p.cell), p.bins);
  std::vector<float> detector(f.model.weights.begin(), f.model.weights.end());
  detector.push_back(static_cast<float>(f.model.bias));
  hog.setSVMDetector(detector);
  std::size_t i = 0;
  std::vector<cv::Rect> found;
  for (auto _ : state) {
    hog.detectMultiScale(f.frames[i++ % f.frames.size()].bgr, found, 0.0, cv::Size(8, 8), cv::Size(0, 0), 1.1);
    benchmark::DoNotOptimize(found);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_SlidingWindowHog)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
