#include "perception/camera/hog_features.hpp"

#include <stdexcept>
#include <string>

#include <opencv2/imgproc.hpp>

namespace fsd {

namespace {
constexpr int kMaxWindow = 256;
// OpenCV's HOG is built for blocks of 2 x 2 cells and about 9 bins: a block of one cell with 2 bins crashed in
// HOGDescriptor::compute (found by cone_model_fuzz), so the geometry is held to what it is made for.
constexpr int kMinBins = 6, kMaxBins = 18;
constexpr std::size_t kMaxFeatures = 100000;  // far above any useful cone window; bounds a model file's size
}  // namespace

std::string HogParameters::check() const {
  const auto in = [](int v, int lo, int hi) { return v >= lo && v <= hi; };
  if (!in(window_width, 8, kMaxWindow) || !in(window_height, 8, kMaxWindow))
    return "window must be 8..256 px on each side";
  if (!in(cell, 4, 64) || block != 2 * cell || block > std::min(window_width, window_height))
    return "cell must be 4..64 px and a block 2 x 2 cells, no larger than the window";
  if (stride != cell && stride != block) return "stride must be one cell or one block";
  if ((window_width - block) % stride != 0 || (window_height - block) % stride != 0)
    return "window minus block must be a multiple of the stride";
  if (!in(bins, kMinBins, kMaxBins)) return "bins must be 6..18";
  if (descriptor_size() > kMaxFeatures)
    return "the geometry gives " + std::to_string(descriptor_size()) + " features, more than " +
           std::to_string(kMaxFeatures);
  return {};
}

std::size_t HogParameters::descriptor_size() const {
  const auto blocks_x = static_cast<std::size_t>((window_width - block) / stride + 1);
  const auto blocks_y = static_cast<std::size_t>((window_height - block) / stride + 1);
  const auto cells = static_cast<std::size_t>((block / cell) * (block / cell));
  return blocks_x * blocks_y * cells * static_cast<std::size_t>(bins);
}

HogFeatures::HogFeatures(const HogParameters& p) : p_(p) {
  if (const std::string problem = p.check(); !problem.empty())
    throw std::invalid_argument("HOG parameters: " + problem);
  hog_ = cv::HOGDescriptor(cv::Size(p.window_width, p.window_height), cv::Size(p.block, p.block),
                           cv::Size(p.stride, p.stride), cv::Size(p.cell, p.cell), p.bins);
}

void HogFeatures::compute(const cv::Mat& roi, std::vector<float>& out) const {
  if (roi.empty() || (roi.type() != CV_8UC3 && roi.type() != CV_8UC1))
    throw std::invalid_argument("HOG features need a non-empty 8-bit BGR or grey image");
  cv::Mat grey;
  if (roi.channels() == 3)
    cv::cvtColor(roi, grey, cv::COLOR_BGR2GRAY);
  else
    grey = roi;
  const cv::Size window(p_.window_width, p_.window_height);
  cv::Mat sized;
  // Area averaging when shrinking (no aliasing of the stripes), bilinear when enlarging a far cone's few pixels.
  const bool shrink = grey.cols >= window.width && grey.rows >= window.height;
  cv::resize(grey, sized, window, 0, 0, shrink ? cv::INTER_AREA : cv::INTER_LINEAR);
  hog_.compute(sized, out, window, cv::Size(0, 0));
}

}  // namespace fsd
