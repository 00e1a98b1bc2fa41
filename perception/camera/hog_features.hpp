#pragma once
// HOG features of an ROI (the paper's §III.B.2): the ROI in grey, resized to a fixed window, described by OpenCV's
// HOGDescriptor. One function for training and for classification, so both see the same features.
#include <cstddef>
#include <vector>

#include <opencv2/core/mat.hpp>
#include <opencv2/objdetect.hpp>

namespace fsd {

// The descriptor's geometry, stored with the model: a model only applies to features of the same geometry.
struct HogParameters {
  int window_width = 32;  // px; a cone ROI is about 1.5 times as tall as wide
  int window_height = 48;
  int block = 16;  // px, square blocks of 2 × 2 cells
  int stride = 8;  // px between blocks
  int cell = 8;    // px
  int bins = 9;    // orientation bins over 0..180°

  bool operator==(const HogParameters&) const = default;
  // Empty when the geometry is one HOGDescriptor accepts, else what is wrong.
  std::string check() const;  // blocks of 2 x 2 cells, stride a cell or a block, 6..18 bins
  std::size_t descriptor_size() const;
};

class HogFeatures {
 public:
  // Throws std::invalid_argument for a geometry check() rejects.
  explicit HogFeatures(const HogParameters& p = {});
  // The ROI (CV_8UC3 BGR or CV_8UC1 grey, any size ≥ 1 × 1) resized to the window; `out` gets descriptor_size() values.
  void compute(const cv::Mat& roi, std::vector<float>& out) const;
  const HogParameters& parameters() const { return p_; }
  std::size_t size() const { return p_.descriptor_size(); }

 private:
  HogParameters p_;
  cv::HOGDescriptor hog_;
};

}  // namespace fsd
