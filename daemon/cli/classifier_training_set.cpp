#include "daemon/cli/classifier_training_set.hpp"

#include <algorithm>
#include <cctype>
#include <stdexcept>

#include <opencv2/core.hpp>

#include "drivers/camera/image_file.hpp"
#include "drivers/sim/world/world_random.hpp"

namespace fsd {

namespace {
constexpr double kMinVisible = 0.7;  // a cone hidden more than this is no clean positive

// The tight box of an object of its own size at the candidate, as a person would crop it.
cv::Mat tight_crop(const RenderedFrame& f, const RenderedCandidate& c, sim::Rng& rng) {
  cv::Rect box;
  if (c.is_cone) {
    box = c.truth_box;
  } else {
    ConeProjectionConfig own;
    own.roi_width = std::max(0.1, c.size.width);
    own.roi_height = std::max(0.1, c.size.height);
    own.roi_below = 0.03;
    const CandidateRoi roi = ConeProjector(f.calibration, own).project(c.cone.position, f.bgr.size());
    if (roi.status != RoiStatus::Inside) return {};
    box = roi.pixels;
  }
  // A margin of 0..25 % on each side, drawn independently.
  const auto margin = [&](int side) { return static_cast<int>(std::lround(rng.uniform(0.0, 0.25) * side)); };
  const cv::Point tl(box.x - margin(box.width), box.y - margin(box.height));
  const cv::Point br(box.br().x + margin(box.width), box.br().y + margin(box.height));
  box = cv::Rect(tl, br) & cv::Rect(0, 0, f.bgr.cols, f.bgr.rows);
  if (box.width < 6 || box.height < 8) return {};
  return f.bgr(box);
}

void add(FeatureSet& set, const cv::Mat& crop, bool cone, bool mirrored_too) {
  set.add(crop, cone);
  if (mirrored_too) {
    cv::Mat flipped;
    cv::flip(crop, flipped, 1);
    set.add(flipped, cone);
  }
}

bool is_image(const std::filesystem::path& p) {
  std::string ext = p.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char ch) { return std::tolower(ch); });
  return ext == ".png" || ext == ".jpg" || ext == ".jpeg";
}
}  // namespace

std::vector<std::filesystem::path> image_files(const std::filesystem::path& dir) {
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec)) throw std::invalid_argument(dir.string() + ": not a folder");
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(dir))
    if (entry.is_regular_file() && is_image(entry.path())) files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  return files;
}

std::vector<CleanCandidate> clean_candidates(const RenderedFrame& frame, const ConeProjector& projector) {
  std::vector<CleanCandidate> out;
  for (const auto& c : frame.candidates) {
    if (c.is_cone ? (c.visible_fraction < kMinVisible || c.truncated) : c.crowded) continue;
    const CandidateRoi roi = projector.project(c.cone.position, frame.bgr.size());
    if (roi.status == RoiStatus::Inside) out.push_back({&c, roi});
  }
  return out;
}

TrainingSet build_training_set(const TrainingSetConfig& cfg) {
  TrainingSet set;
  // Real crops first: a bad folder or file is reported before minutes of rendering.
  if (!cfg.real_dir.empty()) {
    for (const bool cone : {true, false}) {
      const std::filesystem::path dir = cfg.real_dir / (cone ? "cone" : "not_cone");
      if (!std::filesystem::is_directory(dir))
        throw std::invalid_argument(cfg.real_dir.string() + ": needs the folders cone/ and not_cone/ (" + dir.string() +
                                    " is missing)");
      const auto files = image_files(dir);
      for (std::size_t i = 0; i < files.size(); ++i) {
        const cv::Mat crop = read_image_file(files[i]);
        if ((i + 1) % static_cast<std::size_t>(cfg.held_back_every) == 0) {
          set.real_held_back.add(crop, cone);
        } else {
          add(set.train, crop, cone, true);
          set.kinds[cone ? "real_cone" : "real_not_cone"] += 2;
          ++set.real_train;
        }
      }
    }
  }
  sim::Rng rng(sim::hash64(cfg.scenes.seed, 0x7E57));
  render_camera_scenes(cfg.scenes, [&](const RenderedFrame& f) {
    const bool held_back = (f.frame + 1) % cfg.held_back_every == 0;
    const ConeProjector projector(f.calibration);
    for (const auto& [c, roi] : clean_candidates(f, projector)) {
      const cv::Mat pixels = cut_roi(f.bgr, roi);
      if (held_back) {
        set.held_back.add(pixels, c->is_cone);
        continue;
      }
      add(set.train, pixels, c->is_cone, true);
      set.kinds[c->kind] += 2;
      if (const cv::Mat tight = tight_crop(f, *c, rng); !tight.empty()) {
        add(set.train, tight, c->is_cone, false);
        ++set.kinds[c->kind];
      }
    }
  });

  return set;
}

}  // namespace fsd
