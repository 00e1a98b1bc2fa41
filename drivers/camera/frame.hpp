#pragma once
// One camera image as it flows from a camera driver to perception (DESIGN.md §3). OpenCV types stay in the drivers
// and perception; common/ does not see them.
#include <cstdint>

#include <opencv2/core/mat.hpp>

#include "common/time.hpp"

namespace fsd {

struct Frame {
  Stamp stamp = 0;        // capture time on the run's clock
  cv::Mat bgr;            // CV_8UC3
  std::uint32_t seq = 0;  // per source, counts delivered frames from 0
};

}  // namespace fsd
